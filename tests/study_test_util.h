// Shared pieces of the study tests: tiny specs, a private reference cache per
// test, and reading a study directory back.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "core/atomic_file.h"
#include "core/image.h"
#include "study/exports.h"
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

// Starts `pathlab study SPEC -o DIR [--resume]` as a child process, its
// stdout and stderr going to LOG; returns its PID.
inline pid_t startStudy(const std::filesystem::path& spec, const std::filesystem::path& out,
                        bool resume, const std::filesystem::path& log) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(fd, STDOUT_FILENO);
        ::dup2(fd, STDERR_FILENO);
        ::execl(PATHLAB_BINARY, PATHLAB_BINARY, "study", spec.c_str(), "-o", out.c_str(),
                resume ? "--resume" : static_cast<char*>(nullptr), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    return pid;
}

// The cells the study's database holds (0 when it does not exist yet).
inline int64_t rowCount(const std::filesystem::path& out) {
    try {
        return ResultsStore((out / "results.sqlite").string(), /*readOnly=*/true).cellCount();
    } catch (const std::exception&) {
        return 0;
    }
}

// SQLite's own check of the whole database file: "ok" when sound.
inline std::string integrityCheck(const std::filesystem::path& db) {
    sqlite3* handle = nullptr;
    std::string result = "cannot open";
    if (sqlite3_open_v2(db.c_str(), &handle, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
        sqlite3_stmt* stmt = nullptr;
        result = "cannot prepare";
        if (sqlite3_prepare_v2(handle, "PRAGMA integrity_check", -1, &stmt, nullptr) == SQLITE_OK) {
            result.clear();
            while (sqlite3_step(stmt) == SQLITE_ROW)
                result += reinterpret_cast<const char*>(sqlite3_column_text(stmt, 0));
        }
        sqlite3_finalize(stmt);
    }
    sqlite3_close(handle);
    return result;
}

// Every file under `dir` that is a temporary of an interrupted write.
inline std::vector<std::string> temporariesUnder(const std::filesystem::path& dir) {
    std::vector<std::string> out;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
        if (isTemporaryName(entry.path().filename().string())) out.push_back(entry.path());
    return out;
}

// Every image file under `dir` reads back whole at `width`×`height` (a
// truncated or half-written file does not decode).
inline void expectEveryImageComplete(const std::filesystem::path& dir, int width, int height) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
        const std::string ext = entry.path().extension().string();
        if (ext != ".exr" && ext != ".png") continue;
        try {
            const Image image = readImage(entry.path().string());
            EXPECT_EQ(image.width, width) << entry.path();
            EXPECT_EQ(image.height, height) << entry.path();
        } catch (const std::exception& e) {
            ADD_FAILURE() << "incomplete image " << entry.path() << ": " << e.what();
        }
    }
}

// What a finished study directory must hold: every expected cell in the
// database exactly once, a sound database, every image of every row there and
// complete, exports that say what the database says, and no temporaries.
// Returns the rows by key.
inline std::map<CellKey, CellRow> expectCompleteStudy(const std::filesystem::path& dir,
                                                      const std::vector<CellKey>& expected,
                                                      int width, int height) {
    EXPECT_EQ(integrityCheck(dir / "results.sqlite"), "ok");
    const std::vector<CellRow> cells = readCells(dir);
    std::map<CellKey, CellRow> byKey;
    for (const CellRow& c : cells)
        EXPECT_TRUE(byKey.emplace(c.key, c).second) << "twice: " << c.image;
    EXPECT_EQ(cells.size(), expected.size());
    for (const CellKey& key : expected) {
        const auto it = byKey.find(key);
        if (it == byKey.end()) {
            ADD_FAILURE() << "missing cell " << key.sampler << " " << key.spp << " spp seed "
                          << key.seed;
            continue;
        }
        const std::filesystem::path exr = dir / it->second.image;
        std::vector<std::filesystem::path> files = {exr};
        if (key.seed == 0) {
            const std::string stem = std::filesystem::path(exr).replace_extension("").string();
            for (const char* suffix : {".png", "-flip.png", "-relse.png"})
                files.push_back(stem + suffix);
        }
        for (const auto& f : files) EXPECT_TRUE(std::filesystem::is_regular_file(f)) << f;
    }
    expectEveryImageComplete(dir, width, height);
    EXPECT_EQ(temporariesUnder(dir), std::vector<std::string>{});
    // The exports are the database's rows, in its order.
    EXPECT_EQ(slurpFile(dir / "results.csv"), cellsCsv(cells));
    const auto json = nlohmann::json::parse(slurpFile(dir / "results.json"));
    EXPECT_EQ(json.at("cells").size(), cells.size());
    for (size_t i = 0; i < cells.size() && i < json.at("cells").size(); ++i) {
        const auto& j = json.at("cells")[i];
        EXPECT_EQ(j.at("sampler"), cells[i].key.sampler);
        EXPECT_EQ(j.at("spp"), cells[i].key.spp);
        EXPECT_EQ(j.at("seed"), cells[i].key.seed);
        EXPECT_EQ(j.at("mse").get<double>(), cells[i].mse);
        EXPECT_EQ(j.at("image"), cells[i].image);
    }
    return byKey;
}

// Every cell of a one-scene study, in any order.
inline std::vector<CellKey> expectedCells(const std::string& scene,
                                          const std::vector<std::string>& samplers,
                                          const std::vector<int>& spp, int seeds) {
    std::vector<CellKey> out;
    for (const std::string& sampler : samplers)
        for (int n : spp)
            for (int seed = 0; seed < seeds; ++seed) out.push_back({scene, sampler, n, seed});
    return out;
}

// The numbers of two renders of the same cell agree exactly (renders are
// deterministic); only times differ.
inline void expectSameMeasurements(const CellRow& a, const CellRow& b) {
    const std::string where =
        a.key.sampler + " " + std::to_string(a.key.spp) + " spp seed " + std::to_string(a.key.seed);
    EXPECT_EQ(a.mse, b.mse) << where;
    EXPECT_EQ(a.relmse, b.relmse) << where;
    EXPECT_EQ(a.flip, b.flip) << where;
    EXPECT_EQ(a.psnr, b.psnr) << where;
    EXPECT_EQ(a.nonFinite, b.nonFinite) << where;
    EXPECT_EQ(a.image, b.image) << where;
}

}  // namespace pathlab::testing
