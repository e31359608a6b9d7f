// The scene suite: `pathlab study --preset suite` (every sampler on scenes
// that differ in what makes them hard) and its small sibling `quick-suite`,
// plus the public pbrt-v4 scenes that `--scenes-dir DIR` adds to them.
// docs/study.md ("The scene suite") gives the scenes, their difficulty tags
// and what the suite costs.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "study/spec.h"

namespace pathlab {

// Difficulty tags the report's verdict groups scenes by.
inline constexpr const char* kDiffuseIndirect = "diffuse/indirect";
inline constexpr const char* kGlossy = "glossy";
inline constexpr const char* kRefractive = "refractive";
inline constexpr const char* kEnvironment = "environment";
inline constexpr const char* kDepthOfField = "depth of field";
inline constexpr const char* kManyLights = "many lights";
inline constexpr const char* kTextured = "textured";

// A scene of mmp/pbrt-v4-scenes: its path relative to that repository's root
// and what makes it hard.
struct PublicScene {
    std::string path;
    std::string difficulty;
};

// The public scenes the suite takes when they are at hand.
const std::vector<PublicScene>& publicPbrtScenes();

// Every sampler × spp 1…1024 × 3 seeds on the scenes of our own (hours of
// CPU: docs/study.md gives the estimate). A scene file missing from the
// checkout is left out, with a line on `log`.
StudySpec suitePreset(std::ostream& log);

// Four samplers on four small scenes at 64×64, 1…16 spp: the suite's verdict
// in under a minute, for the test suite.
StudySpec quickSuitePreset();

// Is `name` a preset that --scenes-dir may add public scenes to?
bool presetTakesPublicScenes(const std::string& name);

// Adds to `spec` each public scene whose file exists under `dir`, tagged with
// its difficulty, and says on `log` which were found and which not. Throws
// InputError when `dir` is not a directory.
void addPublicScenes(StudySpec& spec, const std::string& dir, std::ostream& log);

}  // namespace pathlab
