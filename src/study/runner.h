// `pathlab study`: renders every cell of a study (scene × sampler × spp ×
// seed) against each scene's reference, keeps each finished cell in
// DIR/results.sqlite, and ends with the exports, the analysis and a summary.
// A study killed at any moment is finished by running it again with resume.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "study/spec.h"

namespace pathlab {

struct StudyOptions {
    std::filesystem::path dir;
    bool resume = false;  // continue the study in `dir`; else `dir` must be empty
    int threads = 0;      // 0: all cores
};

struct StudyRun {
    int cellsRendered = 0, cellsSkipped = 0;
    int referencesRendered = 0, referencesReused = 0;
    double seconds = 0;
    nlohmann::ordered_json analysis;
};

// The renderer's limit (validateRenderSettings).
inline constexpr int kMaxStudyThreads = 4096;

// Throws InputError for options that cannot work whatever the spec: no
// directory named, a file where the directory should be, a thread count
// out of range.
void checkStudyOptions(const StudyOptions& options);

// Throws InputError for bad options, a scene that cannot be loaded, or a
// directory that cannot be used (not empty without resume, another study's
// directory or a changed scene, not writable), before anything is written.
StudyRun runStudy(const StudySpec& spec, const StudyOptions& options);

}  // namespace pathlab
