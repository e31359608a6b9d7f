// A study spec: which scenes, samplers, sample counts and seeds to render, at
// which settings, against which reference. Read from TOML (docs/study-spec.toml
// is the commented example), strictly: anything unexpected is an InputError
// naming the key and its line, so a typo never silently changes a study.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "render/integrator_settings.h"

namespace pathlab {

// Differs from every seed a study's cells use (0, 1, 2, …), so the reference's
// random numbers are independent of every cell's — a cell sharing them would
// look closer to the reference than it is.
inline constexpr uint64_t kDefaultReferenceSeed = 2718281828;

// The most sample ranges a spec may ask a reference to be split into.
inline constexpr int kMaxReferenceRangeCount = 4096;

struct ReferenceSpec {
    int spp = 4096;
    std::string sampler = "independent";
    uint64_t seed = kDefaultReferenceSeed;
    // The number of sample ranges it is rendered in (reference_ranges.h);
    // 0 = automatic: at most 16 ranges of at least 64 samples.
    int ranges = 0;
};

// One scene of a study: `name` names its rows and folders (the built-in name,
// or the file's stem), `source` is what loadScene() gets (built-in name or
// absolute path). `origin` says where the spec names it ("spec.toml:3: key
// 'scenes[0]'", empty for a preset), so a scene that fails to load is
// reported against the line that asked for it. `difficulty` says what makes
// the scene hard ("glossy", "environment", …; empty when untold): the
// report's verdict groups scenes by it. It changes no pixel.
struct StudyScene {
    std::string name, source;
    std::string origin = {};
    std::string difficulty = {};
};

// Another renderer's images of a scene, judged beside the study's own cells
// ([[external]] in docs/study-spec.toml; study/external.h finds them). Paths
// are absolute; `origin` names the spec line of the table for messages.
struct ExternalSpec {
    std::string name;       // its samplers appear as "name:sampler"
    std::string scene;      // a study scene's name, or any name with `reference`
    std::string images;     // pattern with {sampler}, {spp} and {seed}
    std::string times;      // optional CSV sampler,spp,seed,seconds; "" when none
    std::string reference;  // optional image; "" for the study's reference
    std::string origin = {};
};

struct StudySpec {
    std::string name = "study";
    std::vector<StudyScene> scenes;
    std::vector<std::string> samplers;
    std::vector<int> spp;  // ascending, distinct
    int seeds = 1;         // cells use seeds 0 … seeds−1
    Vec2i resolution{256, 256};
    int maxDepth = 8;
    bool russianRoulette = true;
    int rouletteDepth = kDefaultRouletteDepth;  // bounces before roulette may end a path
    // How next-event estimation chooses a light in every render of the study,
    // the reference's included: uniform, power or bvh; "" = each scene's own
    // (power unless its file says otherwise).
    std::string lightSampler;
    // Every render of the study, the reference's included, in spectral mode
    // (RenderSettings::spectral).
    bool spectral = false;
    // Spectral mode's wavelength sampling (RenderSettings::wavelengths): the
    // key `wavelengths = "hero"`; anything but the default needs `spectral`.
    spectral::WavelengthSampling wavelengths = spectral::WavelengthSampling::Visible;
    ReferenceSpec reference;
    std::vector<std::string> metrics{"mse", "relmse", "psnr", "flip"};
    std::optional<double> timeBudgetSeconds;
    std::vector<ExternalSpec> externals;

    bool wants(const std::string& metric) const;
};

// The metric names a spec may list; "mse" is always computed.
const std::vector<std::string>& knownStudyMetrics();

// Parses and validates TOML text. `sourceName` prefixes messages
// ("spec.toml:7: …"); relative scene paths are resolved against `baseDir`.
StudySpec parseStudySpec(const std::string& text, const std::string& sourceName,
                         const std::string& baseDir);

// Reads and parses a spec file; relative scene paths are relative to it.
StudySpec loadStudySpec(const std::string& path);

// The spec as canonical TOML: every key explicit, scene paths absolute. What a
// study directory keeps as spec.toml, and what --resume compares.
std::string studySpecToToml(const StudySpec& spec);

// The first key whose value differs between two specs, or "" when equal.
std::string firstSpecDifference(const StudySpec& a, const StudySpec& b);

}  // namespace pathlab
