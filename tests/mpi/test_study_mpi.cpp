// `pathlab study` under mpirun (docs/cluster.md): the same study as one
// process, bit for bit; a rank killed mid-study, then --resume; bad input.
#include <dirent.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <thread>

#include "core/image.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// mpirun as CI runs it: more ranks than the 2 cores, none bound to a core;
// each rank gets the test's reference cache.
std::string mpirunCommand(int ranks) {
    return std::string(PATHLAB_MPIEXEC) + " --oversubscribe --bind-to none -np " +
           std::to_string(ranks) + " -x PATHLAB_CACHE " + PATHLAB_BINARY;
}

testing::CliResult runMpi(int ranks, const std::string& args, const fs::path& dir) {
    const auto out = dir / "mpi-stdout.txt", err = dir / "mpi-stderr.txt";
    const std::string cmd = mpirunCommand(ranks) + " " + args + " >" + out.string() + " 2>" +
                            err.string() + " </dev/null";
    const int status = std::system(cmd.c_str());
    testing::CliResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = testing::slurpFile(out);
    r.err = testing::slurpFile(err);
    return r;
}

std::map<CellKey, CellRow> byKey(const std::vector<CellRow>& cells) {
    std::map<CellKey, CellRow> out;
    for (const CellRow& c : cells) EXPECT_TRUE(out.emplace(c.key, c).second) << "twice";
    return out;
}

void expectSamePixels(const fs::path& a, const fs::path& b) {
    const Image x = readImage(a.string()), y = readImage(b.string());
    EXPECT_EQ(x.width, y.width) << a;
    EXPECT_EQ(x.height, y.height) << a;
    EXPECT_TRUE(x.rgb == y.rgb) << a << " and " << b << " differ";
}

const std::vector<std::string> kSamplers = {"standard", "halton-rd", "independent"};

TEST(MpiStudy, ThreeRanksMakeTheSingleProcessStudy) {
    const auto dir = testing::scratchDirectory("mpi-equal");
    const auto spec = testing::writeSpec(dir, "tiny.toml", testing::tinySpec());
    // Separate caches: each run renders its own reference.
    testing::usePrivateCache(dir / "one");
    const auto one = testing::runPathlab(
        "study " + spec.string() + " -o " + (dir / "one").string() + "/study", dir);
    ASSERT_EQ(one.exitCode, 0) << one.err;
    testing::usePrivateCache(dir / "three");
    const auto three =
        runMpi(3, "study " + spec.string() + " -o " + (dir / "three/study").string(), dir);
    ASSERT_EQ(three.exitCode, 0) << three.err;
    EXPECT_NE(three.err.find("on 3 ranks"), std::string::npos) << three.err;
    EXPECT_NE(three.err.find("rendering reference"), std::string::npos) << three.err;

    const auto expected = testing::expectedCells("cornell-box", kSamplers, {1, 4, 16}, 2);
    const auto a = testing::expectCompleteStudy(dir / "one/study", expected, 32, 32);
    const auto b = testing::expectCompleteStudy(dir / "three/study", expected, 32, 32);
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [key, row] : a) {
        ASSERT_TRUE(b.count(key));
        testing::expectSameMeasurements(row, b.at(key));
        EXPECT_EQ(row.flipMedian, b.at(key).flipMedian);
        EXPECT_EQ(row.mseEdge, b.at(key).mseEdge);
        EXPECT_EQ(row.bias, b.at(key).bias);
        expectSamePixels(dir / "one/study" / row.image, dir / "three/study" / b.at(key).image);
    }
    expectSamePixels(dir / "one/study/references/cornell-box.exr",
                     dir / "three/study/references/cornell-box.exr");
    fs::remove_all(dir);
}

// The process mpirun started as `rank` (its child whose environment says so).
pid_t findRank(pid_t mpirun, int rank) {
    const std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
    for (const auto& entry : fs::directory_iterator("/proc")) {
        const std::string name = entry.path().filename();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        const std::string stat = testing::slurpFile(entry.path() / "stat");
        const auto close = stat.rfind(')');
        if (close == std::string::npos) continue;
        int ppid = 0;
        char state = 0;
        if (std::sscanf(stat.c_str() + close + 1, " %c %d", &state, &ppid) != 2) continue;
        if (ppid != mpirun) continue;
        const std::string env = testing::slurpFile(entry.path() / "environ");
        for (size_t at = 0; at < env.size(); at = env.find('\0', at) + 1) {
            if (env.compare(at, want.size() + 1, want + '\0') == 0) return pid_t(std::stoi(name));
            if (env.find('\0', at) == std::string::npos) break;
        }
    }
    return 0;
}

pid_t startMpiStudy(const fs::path& spec, const fs::path& out, const fs::path& log) {
    // exec: mpirun keeps the shell's PID, the parent of the ranks.
    const std::string cmd = "exec " + mpirunCommand(3) + " study " + spec.string() + " -o " +
                            out.string() + " >" + log.string() + " 2>&1 </dev/null";
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    return pid;
}

// 3 samplers × 7 spp × 2 seeds = 42 cells of a 128×128 Cornell box: each render
// long enough (tens of ms on one core) that rank 1 is still rendering when the
// first cell is committed and the test kills it.
std::string killSpec() {
    return "name = \"mpi-kill\"\n"
           "scenes = [\"cornell-box\"]\n"
           "samplers = [\"standard\", \"halton-owen\", \"independent\"]\n"
           "spp = [1, 2, 4, 8, 16, 32, 64]\n"
           "seeds = 2\n"
           "resolution = [128, 128]\n"
           "[reference]\nspp = 128\n";
}

TEST(MpiStudy, RankKilledThenResumeFinishesEveryCellOnce) {
    const auto dir = testing::scratchDirectory("mpi-kill");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "kill.toml", killSpec());
    const auto out = dir / "study";
    const pid_t mpirun = startMpiStudy(spec, out, dir / "killed.log");
    ASSERT_GT(mpirun, 0);
    const auto deadline = Clock::now() + std::chrono::minutes(2);
    int status = 0;
    while (testing::rowCount(out) < 1 && Clock::now() < deadline) {
        ASSERT_EQ(::waitpid(mpirun, &status, WNOHANG), 0)
            << "mpirun ended early: " << testing::slurpFile(dir / "killed.log");
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    const pid_t worker = findRank(mpirun, 1);
    ASSERT_GT(worker, 0) << "no rank 1 under mpirun " << mpirun;
    ::kill(worker, SIGKILL);
    ::waitpid(mpirun, &status, 0);
    const std::string log = testing::slurpFile(dir / "killed.log");
    ASSERT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "finished before the kill";
    // mpirun names the rank that died; rank 0 names what was in flight (its
    // own render too when it has one, which this kill's timing cannot force).
    EXPECT_NE(log.find("process rank 1"), std::string::npos) << log;
    EXPECT_NE(log.find("rank 1: cornell-box"), std::string::npos) << log;
    std::map<CellKey, CellRow> before = byKey(testing::readCells(out));
    ASSERT_LT(before.size(), 42u);

    const auto resumed =
        runMpi(3, "study " + spec.string() + " -o " + out.string() + " --resume", dir);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_EQ(resumed.err.find("rendering reference"), std::string::npos) << resumed.err;
    const auto expected = testing::expectedCells(
        "cornell-box", {"standard", "halton-owen", "independent"}, {1, 2, 4, 8, 16, 32, 64}, 2);
    const auto after = testing::expectCompleteStudy(out, expected, 128, 128);
    // A cell finished before the kill is kept, not rendered again.
    for (const auto& [key, row] : before) {
        ASSERT_TRUE(after.count(key));
        EXPECT_EQ(after.at(key).finishedAt, row.finishedAt);
        EXPECT_EQ(after.at(key).seconds, row.seconds);
    }
    fs::remove_all(dir);
}

// A 48×48 reference of 4096 spp: 16 sample ranges of 256, each long enough
// to kill rank 0 between two of them; one cheap cell.
std::string referenceKillSpec() {
    return "name = \"mpi-ranges\"\n"
           "scenes = [\"cornell-box\"]\n"
           "samplers = [\"independent\"]\n"
           "spp = [1]\n"
           "seeds = 1\n"
           "resolution = [48, 48]\n"
           "[reference]\nspp = 4096\n";
}

int rangeFiles(const fs::path& cache) {
    int n = 0;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(cache, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
        n += it->path().extension() == ".sums";
    return n;
}

// Rank 0 killed while the ranks render the reference's sample ranges: the
// ranges saved stay, a new mpirun of another size renders only the others,
// and the reference is the single-process study's, bit for bit.
TEST(MpiStudy, RankZeroKilledMidReferenceThenResumeKeepsItsRanges) {
    const auto dir = testing::scratchDirectory("mpi-ranges");
    const auto spec = testing::writeSpec(dir, "ranges.toml", referenceKillSpec());
    testing::usePrivateCache(dir / "one");
    const auto one =
        testing::runPathlab("study " + spec.string() + " -o " + (dir / "one/study").string(), dir);
    ASSERT_EQ(one.exitCode, 0) << one.err;

    const fs::path cache = testing::usePrivateCache(dir / "mpi");
    const auto out = dir / "mpi/study";
    const pid_t mpirun = startMpiStudy(spec, out, dir / "killed.log");
    ASSERT_GT(mpirun, 0);
    const auto deadline = Clock::now() + std::chrono::minutes(2);
    int status = 0;
    while (rangeFiles(cache) < 2 && Clock::now() < deadline) {
        ASSERT_EQ(::waitpid(mpirun, &status, WNOHANG), 0)
            << "mpirun ended early: " << testing::slurpFile(dir / "killed.log");
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    const pid_t rankZero = findRank(mpirun, 0);
    ASSERT_GT(rankZero, 0) << "no rank 0 under mpirun " << mpirun;
    ::kill(rankZero, SIGKILL);
    ::waitpid(mpirun, &status, 0);
    ASSERT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "finished before the kill";
    const int kept = rangeFiles(cache);
    ASSERT_GE(kept, 2);
    ASSERT_LT(kept, 16) << testing::slurpFile(dir / "killed.log");

    const auto resumed =
        runMpi(2, "study " + spec.string() + " -o " + out.string() + " --resume", dir);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_NE(resumed.err.find("in 16 sample ranges, " + std::to_string(kept) + " already done"),
              std::string::npos)
        << resumed.err;
    EXPECT_EQ(rangeFiles(cache), 0) << "merged, then removed";
    expectSamePixels(dir / "one/study/references/cornell-box.exr",
                     out / "references/cornell-box.exr");
    fs::remove_all(dir);
}

// A rank that sees another directory under DIR's name (a file system not
// mounted on its host) stops the job before any rendering, with one line,
// and the new study directory is removed again.
TEST(MpiStudy, RankThatCannotReachTheDirectoryFailsFast) {
    const auto dir = testing::scratchDirectory("mpi-unreachable");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "tiny.toml", testing::tinySpec());
    const std::string study = "study " + spec.string() + " -o ";
    // mpirun's multiple-program form: rank 2 is given a directory of its own.
    const std::string cmd =
        std::string(PATHLAB_MPIEXEC) + " --oversubscribe --bind-to none -x PATHLAB_CACHE -np 2 " +
        PATHLAB_BINARY + " " + study + (dir / "shared").string() + " : -np 1 " + PATHLAB_BINARY +
        " " + study + (dir / "elsewhere").string() + " >" + (dir / "out.txt").string() + " 2>" +
        (dir / "err.txt").string() + " </dev/null";
    const int status = std::system(cmd.c_str());
    const std::string err = testing::slurpFile(dir / "err.txt");
    ASSERT_TRUE(WIFEXITED(status)) << err;
    EXPECT_EQ(WEXITSTATUS(status), 2) << err;
    const auto first = err.find("pathlab: error: rank 2 (");
    ASSERT_NE(first, std::string::npos) << err;
    EXPECT_NE(err.find("cannot reach the study directory", first), std::string::npos) << err;
    EXPECT_EQ(err.find("pathlab: error:", first + 1), std::string::npos) << err;
    EXPECT_EQ(err.find("reference"), std::string::npos) << "stopped before rendering: " << err;
    EXPECT_FALSE(fs::exists(dir / "shared")) << "what rank 0 began is removed";
    fs::remove_all(dir);
}

TEST(MpiStudy, BadInputSaysSoOnceWithExitCode2) {
    const auto dir = testing::scratchDirectory("mpi-bad");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(
        dir, "bad.toml",
        "name = \"bad\"\nscenes = [\"no-such-scene\"]\nsamplers = [\"standard\"]\nspp = [1]\n"
        "resolution = [8, 8]\n[reference]\nspp = 4\n");
    const auto r = runMpi(3, "study " + spec.string() + " -o " + (dir / "out").string(), dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    const auto first = r.err.find("pathlab: error:");
    ASSERT_NE(first, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("pathlab: error:", first + 1), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
