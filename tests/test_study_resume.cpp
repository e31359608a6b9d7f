// kill -9 in the middle of a study, then --resume: every cell exactly once,
// with the same numbers as a study that was never interrupted.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <thread>

#include "core/image.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;

// 3 samplers × 7 spp × 2 seeds = 42 cells of a 48×48 Cornell box: a few
// seconds, long enough to be killed in the middle.
std::string resumeSpec() {
    return "name = \"resume\"\n"
           "scenes = [\"cornell-box\"]\n"
           "samplers = [\"standard\", \"halton-owen\", \"independent\"]\n"
           "spp = [1, 2, 4, 8, 16, 32, 64]\n"
           "seeds = 2\n"
           "resolution = [48, 48]\n"
           "[reference]\nspp = 128\n";
}
constexpr int kCells = 42;

// Starts `pathlab study SPEC -o DIR` as a child with its output in DIR's parent.
pid_t startStudy(const fs::path& spec, const fs::path& out) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int log = ::open((out.string() + ".log").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(log, STDOUT_FILENO);
        ::dup2(log, STDERR_FILENO);
        ::execl(PATHLAB_BINARY, PATHLAB_BINARY, "study", spec.c_str(), "-o", out.c_str(),
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    return pid;
}

int64_t rowCount(const fs::path& out) {
    try {
        return ResultsStore((out / "results.sqlite").string(), /*readOnly=*/true).cellCount();
    } catch (const std::exception&) {
        return 0;  // not created yet
    }
}

std::map<CellKey, CellRow> byKey(const std::vector<CellRow>& cells) {
    std::map<CellKey, CellRow> out;
    for (const CellRow& c : cells) EXPECT_TRUE(out.emplace(c.key, c).second) << "twice";
    return out;
}

void expectSameMeasurements(const CellRow& a, const CellRow& b) {
    const std::string where =
        a.key.sampler + " " + std::to_string(a.key.spp) + " spp seed " + std::to_string(a.key.seed);
    EXPECT_EQ(a.mse, b.mse) << where;
    EXPECT_EQ(a.relmse, b.relmse) << where;
    EXPECT_EQ(a.flip, b.flip) << where;
    EXPECT_EQ(a.psnr, b.psnr) << where;
    EXPECT_EQ(a.image, b.image) << where;
}

TEST(StudyResume, KilledStudyResumesWithEveryCellExactlyOnce) {
    const auto dir = testing::scratchDirectory("study-resume");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "resume.toml", resumeSpec());

    const auto killed = dir / "killed";
    const pid_t pid = startStudy(spec, killed);
    ASSERT_GT(pid, 0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(3);
    while (rowCount(killed) < 4 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the study finished before it could be killed";
    const int64_t before = rowCount(killed);
    EXPECT_GE(before, 4);
    EXPECT_LT(before, kCells);

    const auto resumed =
        testing::runPathlab("study " + spec.string() + " -o " + killed.string() + " --resume", dir);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_EQ(resumed.err.find("rendering reference"), std::string::npos) << resumed.err;
    const auto whole =
        testing::runPathlab("study " + spec.string() + " -o " + (dir / "whole").string(), dir);
    ASSERT_EQ(whole.exitCode, 0) << whole.err;

    const auto a = byKey(testing::readCells(killed)), b = byKey(testing::readCells(dir / "whole"));
    ASSERT_EQ(a.size(), size_t(kCells));
    ASSERT_EQ(b.size(), size_t(kCells));
    for (const auto& [key, row] : a) {
        ASSERT_TRUE(b.count(key));
        expectSameMeasurements(row, b.at(key));
        EXPECT_EQ(readImage((killed / row.image).string()).width, 48);
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
