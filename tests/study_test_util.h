// Shared pieces of the study tests: tiny specs, a private reference cache per
// test, and reading a study directory back.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.h"
#include "study/results_store.h"

namespace pathlab::testing {

// Points $PATHLAB_CACHE (inherited by the pathlab processes the test starts)
// at a directory of its own, so tests neither share nor pollute a cache.
inline std::filesystem::path usePrivateCache(const std::filesystem::path& scratch) {
    const auto cache = scratch / "cache";
    std::filesystem::create_directories(cache);
    ::setenv("PATHLAB_CACHE", cache.c_str(), 1);
    return cache;
}

inline std::filesystem::path writeSpec(const std::filesystem::path& dir, const std::string& name,
                                       const std::string& text) {
    const auto path = dir / name;
    std::ofstream(path) << text;
    return path;
}

// A small Cornell box study: 32×32, three samplers, three spp, two seeds.
inline std::string tinySpec(const std::string& extra = "") {
    return "name = \"tiny\"\n"
           "scenes = [\"cornell-box\"]\n"
           "samplers = [\"standard\", \"halton-rd\", \"independent\"]\n"
           "spp = [1, 4, 16]\n"
           "seeds = 2\n"
           "resolution = [32, 32]\n"
           "time_budget_seconds = 0.01\n" +
           extra +
           "[reference]\n"
           "spp = 256\n";
}

inline std::vector<CellRow> readCells(const std::filesystem::path& studyDir) {
    ResultsStore store((studyDir / "results.sqlite").string(), /*readOnly=*/true);
    return store.cells();
}

}  // namespace pathlab::testing
