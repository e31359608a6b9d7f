// Fuzzes the study-spec TOML parser (docs/study-spec.toml) and checks what
// `pathlab study --resume` relies on: a valid spec written as canonical TOML
// reads back as the same spec. Relative scene paths resolve against a scratch
// directory holding "tri.obj" and "scene.json" (existence is all the parser
// checks).
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "fuzz_util.h"
#include "study/spec.h"

namespace {

const std::string& specDir() {
    static const std::string dir = [] {
        pathlab::fuzz::writeScratchFile("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        pathlab::fuzz::writeScratchFile("scene.json", "{}\n");
        return pathlab::fuzz::scratchDir().string();
    }();
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pathlab;
    StudySpec spec;
    try {
        spec = parseStudySpec(std::string(fuzz::asText(data, size)), "fuzz.toml", specDir());
    } catch (const InputError&) {
        return 0;
    }
    const std::string toml = studySpecToToml(spec);
    std::string difference;
    try {
        difference = firstSpecDifference(spec, parseStudySpec(toml, "spec.toml", specDir()));
    } catch (const InputError& e) {
        std::fprintf(stderr, "a written spec does not read back: %s\n%s", e.what(), toml.c_str());
        std::abort();
    }
    if (!difference.empty()) {
        std::fprintf(stderr, "a written spec reads back with a different '%s':\n%s",
                     difference.c_str(), toml.c_str());
        std::abort();
    }
    return 0;
}
