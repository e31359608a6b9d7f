// A full disk: pathlab stops with one line naming the file it could not
// write (exit code 2), leaves no partial file, keeps what it had finished —
// and a study resumed once there is room again ends complete.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

#include "small_filesystem.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using testing::runPathlab;

const std::vector<std::string> kSamplers = {"standard", "independent"};
const std::vector<int> kSpp = {1, 4, 16};
std::string fullDiskSpec() {
    return "name = \"full\"\n"
           "scenes = [\"cornell-box\"]\n"
           "samplers = [\"standard\", \"independent\"]\n"
           "spp = [1, 4, 16]\n"
           "seeds = 2\n"
           "resolution = [32, 32]\n"
           "[reference]\nspp = 64\n";
}

// Bytes the files under `dir` occupy in 4 KiB pages (as on a tmpfs).
size_t diskUsage(const fs::path& dir) {
    size_t total = 0;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file()) total += (entry.file_size() + 4095) / 4096 * 4096;
    return total;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

// The failure is one line, the last, naming the problem and a file in `dir`.
void expectOneNoSpaceLine(const std::string& err, const fs::path& dir) {
    const auto all = lines(err);
    ASSERT_FALSE(all.empty());
    int errorLines = 0;
    for (const std::string& line : all) errorLines += line.find("error") != std::string::npos;
    EXPECT_EQ(errorLines, 1) << err;
    const std::string prefix = "pathlab: error: no space left on device writing '" + dir.string();
    EXPECT_EQ(all.back().rfind(prefix, 0), 0u) << err;
}

#define REQUIRE_SMALL_FS(fs) \
    if (!(fs).available())   \
    GTEST_SKIP() << "no size-limited file system can be mounted here: " << (fs).why()

TEST(FullDisk, StudyStopsCleanlyAndResumesOnceThereIsRoom) {
    const auto dir = testing::scratchDirectory("full-disk-study");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "full.toml", fullDiskSpec());
    const std::vector<CellKey> expected = testing::expectedCells("cornell-box", kSamplers, kSpp, 2);

    // The whole study on a roomy disk: its numbers and the space it takes.
    const auto whole =
        runPathlab("study " + spec.string() + " -o " + (dir / "whole").string(), dir);
    ASSERT_EQ(whole.exitCode, 0) << whole.err;
    const auto reference = testing::expectCompleteStudy(dir / "whole", expected, 32, 32);
    const size_t need = diskUsage(dir / "whole");

    auto owner = std::make_unique<testing::SmallFileSystem>(dir / "small", 2 * need + (256 << 10));
    testing::SmallFileSystem& small = *owner;
    REQUIRE_SMALL_FS(small);
    std::printf("small file system: %s\n", small.how().c_str());
    // Room for a tenth … nine tenths of the study: the disk fills up while
    // writing the reference, cell images, the database or the exports.
    for (int tenths : {1, 3, 5, 7, 9}) {
        SCOPED_TRACE(std::to_string(tenths) + " tenths of the room the study needs");
        const fs::path out = small.root() / ("s" + std::to_string(tenths));
        small.fill(need * tenths / 10);
        const auto full = runPathlab("study " + spec.string() + " -o " + out.string(), dir);
        EXPECT_EQ(full.exitCode, 2) << full.err;
        expectOneNoSpaceLine(full.err, out);
        // Nothing half-written; the database sound and every row's images
        // there (read with room again: a reader of a WAL database writes).
        // A disk that filled while the study's first files were written
        // leaves no directory at all.
        if (fs::exists(out)) {
            EXPECT_EQ(testing::temporariesUnder(out), std::vector<std::string>{});
            testing::expectEveryImageComplete(out, 32, 32);
        }
        small.removeFiller();
        if (fs::exists(out / "results.sqlite")) {
            EXPECT_EQ(testing::integrityCheck(out / "results.sqlite"), "ok");
            std::vector<CellRow> cells;  // none when the disk filled before the tables
            if (testing::rowCount(out) > 0) cells = testing::readCells(out);
            EXPECT_LE(cells.size(), expected.size());
            for (const CellRow& c : cells) EXPECT_TRUE(fs::is_regular_file(out / c.image));
        }

        const auto resumed =
            runPathlab("study " + spec.string() + " -o " + out.string() + " --resume", dir);
        ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
        const auto cells = testing::expectCompleteStudy(out, expected, 32, 32);
        for (const auto& [key, row] : cells)
            if (reference.count(key)) testing::expectSameMeasurements(row, reference.at(key));
        fs::remove_all(out);
        if (::testing::Test::HasFailure()) break;
    }
    owner.reset();  // unmounted before the scratch directory goes
    fs::remove_all(dir);
}

// render -o, compare --error-map and points -o onto a full disk: one line, no
// file, and a file already there under that name unchanged.
TEST(FullDisk, SingleOutputsAreAllOrNothing) {
    const auto dir = testing::scratchDirectory("full-disk-outputs");
    auto owner = std::make_unique<testing::SmallFileSystem>(dir / "small", 1 << 20);
    testing::SmallFileSystem& small = *owner;
    REQUIRE_SMALL_FS(small);
    const fs::path root = small.root();
    // Two images to compare, outside the small file system.
    ASSERT_EQ(
        runPathlab("render --scene cornell-box --spp 1 --size 96x96 -o " + (dir / "a.exr").string(),
                   dir)
            .exitCode,
        0);
    ASSERT_EQ(
        runPathlab("render --scene cornell-box --spp 2 --size 96x96 -o " + (dir / "b.exr").string(),
                   dir)
            .exitCode,
        0);
    const std::string render = "render --scene cornell-box --spp 1 --size 96x96 -o ";
    const std::string compare =
        "compare " + (dir / "a.exr").string() + " " + (dir / "b.exr").string() + " --error-map ";
    const std::string points = "points --sampler halton --count 4096 --dims 0,1 -o ";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {render, "r.exr"}, {render, "r.png"}, {compare, "map.png"}, {points, "p.csv"}};
    for (const auto& [command, name] : cases) {
        SCOPED_TRACE(command + name);
        // An earlier, smaller output under the same name, then a full disk.
        const fs::path kept = root / ("kept-" + name), fresh = root / ("new-" + name);
        const std::string first = command.rfind("render", 0) == 0
                                      ? "render --scene cornell-box --spp 1 --size 8x8 -o "
                                      : (command.rfind("points", 0) == 0
                                             ? "points --sampler halton --count 4 --dims 0,1 -o "
                                             : command);
        ASSERT_EQ(runPathlab(first + kept.string(), dir).exitCode, 0);
        const std::string before = testing::slurpFile(kept);
        small.fill(0);
        for (const fs::path& target : {kept, fresh}) {
            const auto r = runPathlab(command + target.string(), dir);
            EXPECT_EQ(r.exitCode, 2) << r.err;
            EXPECT_EQ(r.errLines(), 1) << r.err;
            EXPECT_EQ(r.err, "pathlab: error: no space left on device writing '" + target.string() +
                                 "'\n");
        }
        EXPECT_EQ(testing::slurpFile(kept), before);
        EXPECT_FALSE(fs::exists(fresh));
        EXPECT_EQ(testing::temporariesUnder(root), std::vector<std::string>{});
        small.removeFiller();
        fs::remove(kept);
    }
    owner.reset();
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
