// kill -9 in the middle of a study, then --resume: every cell exactly once,
// with the same numbers as a study that was never interrupted.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <thread>

#include "core/image.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

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

std::map<CellKey, CellRow> byKey(const std::vector<CellRow>& cells) {
    std::map<CellKey, CellRow> out;
    for (const CellRow& c : cells) EXPECT_TRUE(out.emplace(c.key, c).second) << "twice";
    return out;
}

TEST(StudyResume, KilledStudyResumesWithEveryCellExactlyOnce) {
    const auto dir = testing::scratchDirectory("study-resume");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "resume.toml", resumeSpec());

    const auto killed = dir / "killed";
    const pid_t pid = testing::startStudy(spec, killed, false, dir / "killed.log");
    ASSERT_GT(pid, 0);
    const auto deadline = Clock::now() + std::chrono::minutes(3);
    while (testing::rowCount(killed) < 4 && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the study finished before it could be killed";
    const int64_t before = testing::rowCount(killed);
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
        testing::expectSameMeasurements(row, b.at(key));
        EXPECT_EQ(readImage((killed / row.image).string()).width, 48);
    }
    fs::remove_all(dir);
}

// 3 samplers × 4 spp × 2 seeds = 24 cells of a 32×32 Cornell box, about a
// second on two cores: short, so many kills fit in a test.
const std::vector<std::string> kKillSamplers = {"standard", "halton-owen", "independent"};
const std::vector<int> kKillSpp = {1, 2, 4, 8};
std::string killSpec() {
    return "name = \"kill\"\n"
           "scenes = [\"cornell-box\"]\n"
           "samplers = [\"standard\", \"halton-owen\", \"independent\"]\n"
           "spp = [1, 2, 4, 8]\n"
           "seeds = 2\n"
           "resolution = [32, 32]\n"
           "time_budget_seconds = 0.001\n"
           "[reference]\nspp = 64\n";
}

// Runs `pathlab study` (with --resume when asked) and kills it with SIGKILL
// after `delay`, unless it exits first. True when it was killed; a run that
// exits on its own must succeed.
bool runAndKill(const fs::path& spec, const fs::path& out, bool resume, Clock::duration delay,
                const fs::path& log) {
    const pid_t pid = testing::startStudy(spec, out, resume, log);
    EXPECT_GT(pid, 0);
    const auto killAt = Clock::now() + delay;
    int status = 0;
    while (Clock::now() < killAt) {
        if (::waitpid(pid, &status, WNOHANG) == pid) {
            EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
                << "status " << status << ": " << testing::slurpFile(log);
            return false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    if (WIFSIGNALED(status)) return true;
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
        << "status " << status << ": " << testing::slurpFile(log);
    return false;
}

// kill -9 at random moments over the whole run — reference, cells, images,
// database commits, exports — again and again, each time resuming: the study
// ends complete, every cell once, with the numbers of an uninterrupted run.
TEST(StudyResume, SurvivesRepeatedKillsAtRandomMoments) {
    const auto dir = testing::scratchDirectory("study-kill");
    const auto spec = testing::writeSpec(dir, "kill.toml", killSpec());
    const std::vector<CellKey> expected =
        testing::expectedCells("cornell-box", kKillSamplers, kKillSpp, 2);

    // The uninterrupted study: its numbers, and how long a whole run takes
    // (reference included, with an empty cache).
    testing::usePrivateCache(dir / "baseline");
    const auto start = Clock::now();
    const auto whole =
        testing::runPathlab("study " + spec.string() + " -o " + (dir / "whole").string(), dir);
    const Clock::duration runTime = Clock::now() - start;
    ASSERT_EQ(whole.exitCode, 0) << whole.err;
    const auto reference = testing::expectCompleteStudy(dir / "whole", expected, 32, 32);

    // Fixed seed: the same sequence of moments (as fractions of the run time)
    // every time the test runs.
    std::mt19937 rng(20261122);
    std::uniform_real_distribution<double> moment(0.0, 1.0);
    testing::usePrivateCache(dir / "killed-cache");  // the first run renders its reference
    constexpr int kKills = 24;
    int kills = 0, rounds = 0;
    while (kills < kKills) {
        const auto out = dir / ("round" + std::to_string(rounds++));
        bool resume = false;
        for (int attempt = 0; attempt < 100; ++attempt) {
            const auto delay = std::chrono::duration_cast<Clock::duration>(runTime * moment(rng));
            const bool killed = runAndKill(spec, out, resume, delay, dir / "run.log");
            if (::testing::Test::HasFailure()) FAIL() << "a run failed in round " << rounds;
            if (!killed) break;  // finished on its own
            ++kills;
            resume = true;
        }
        // Whatever the kills left, one more resume finishes the study.
        const auto last = testing::runPathlab(
            "study " + spec.string() + " -o " + out.string() + " --resume", dir);
        ASSERT_EQ(last.exitCode, 0) << last.err;
        const auto cells = testing::expectCompleteStudy(out, expected, 32, 32);
        for (const auto& [key, row] : cells)
            if (reference.count(key)) testing::expectSameMeasurements(row, reference.at(key));
        if (::testing::Test::HasFailure()) FAIL() << "round " << rounds << " in " << out;
        fs::remove_all(out);
    }
    EXPECT_GE(kills, kKills);
    std::printf("%d kills in %d rounds; a whole run takes %.2f s\n", kills, rounds,
                std::chrono::duration<double>(runTime).count());
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
