// What a study records per cell is enough to regenerate it: the same
// commit, settings and seed give the same bytes — and how many NaN/Inf
// samples each render discarded is kept with it.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>

#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using testing::runPathlab;

// The cells' settings as `pathlab render` options, from the cell's row and
// the study table (which the whole study shares).
std::string renderArgs(const std::string& scene, const CellRow& c,
                       const std::map<std::string, std::string>& study) {
    return "render --scene " + scene + " --sampler " + c.key.sampler + " --spp " +
           std::to_string(c.key.spp) + " --seed " + std::to_string(c.key.seed) + " --size " +
           std::to_string(c.width) + "x" + std::to_string(c.height) + " --max-depth " +
           std::to_string(c.maxDepth) + " --threads " + std::to_string(c.threads) +
           " --roulette-depth " + study.at("roulette_depth") +
           (study.at("russian_roulette") == "true" ? "" : " --no-russian-roulette");
}

std::map<std::string, std::string> studyTable(const fs::path& dir) {
    ResultsStore store((dir / "results.sqlite").string(), /*readOnly=*/true);
    return store.studyValues();
}

std::string commandOutput(const std::string& command) {
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(command.c_str(), "r"), ::pclose);
    std::string out;
    char buffer[256];
    while (pipe && std::fgets(buffer, sizeof buffer, pipe.get())) out += buffer;
    return out;
}

// results.csv without the two columns that say when and how fast.
std::string csvWithoutTimes(const fs::path& csv) {
    std::string out = testing::slurpFile(csv);
    // seconds is the 5th column, finished_at the last.
    out = std::regex_replace(out, std::regex(R"(^((?:[^,\n]*,){4})[^,\n]*)", std::regex::multiline),
                             "$1");
    return std::regex_replace(out, std::regex(R"(,[^,\n]*$)", std::regex::multiline), "");
}

TEST(StudyRecords, EveryCellRegeneratesByteForByteFromItsRecord) {
    const auto dir = testing::scratchDirectory("study-records");
    testing::usePrivateCache(dir);
    const auto spec =
        testing::writeSpec(dir, "r.toml",
                           "name = \"records\"\nscenes = [\"cornell-box\"]\n"
                           // halton: the seed does not randomise it, so its seed-1
                           // cells are copies of one render, and must still be what
                           // `render --seed 1` makes.
                           "samplers = [\"sobol-owen\", \"halton\", \"independent\"]\n"
                           "spp = [1, 4]\nseeds = 2\n"
                           "resolution = [24, 20]\nmax_depth = 5\nroulette_depth = 1\n"
                           "[reference]\nspp = 32\n");
    for (const char* out : {"a", "b"})
        ASSERT_EQ(
            runPathlab("study " + spec.string() + " -o " + (dir / out).string(), dir).exitCode, 0);
    const auto cells = testing::readCells(dir / "a");
    const auto study = studyTable(dir / "a");
    ASSERT_EQ(cells.size(), 12u);

    // The commit recorded is the source tree's, marked when it has changes.
    const std::string git = std::string("git -C '") + PATHLAB_SOURCE_DIR + "' ";
    std::string head = commandOutput(git + "rev-parse HEAD 2>/dev/null");
    if (!head.empty()) head.pop_back();
    std::string expectedCommit = "unknown";
    if (head.size() == 40)
        expectedCommit =
            head +
            (commandOutput(git + "status --porcelain --untracked-files=no 2>/dev/null").empty()
                 ? ""
                 : "-dirty");
    EXPECT_EQ(study.at("git_commit"), expectedCommit);
    EXPECT_EQ(study.at("russian_roulette"), "true");
    EXPECT_EQ(study.at("roulette_depth"), "1");

    for (const CellRow& c : cells) {
        SCOPED_TRACE(c.image);
        EXPECT_EQ(c.gitCommit, expectedCommit);
        EXPECT_EQ(c.maxDepth, 5);
        EXPECT_EQ(c.width, 24);
        EXPECT_EQ(c.height, 20);
        // Regenerated from the record alone: the very same file.
        const fs::path again = dir / "again.exr";
        const auto r =
            runPathlab(renderArgs("cornell-box", c, study) + " -o " + again.string(), dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(testing::slurpFile(again), testing::slurpFile(dir / "a" / c.image));
    }
    // Two runs of a study: the same bytes in every image and the same numbers.
    for (const auto& entry : fs::recursive_directory_iterator(dir / "a" / "images")) {
        if (!entry.is_regular_file()) continue;
        const fs::path other = dir / "b" / fs::relative(entry.path(), dir / "a");
        EXPECT_EQ(testing::slurpFile(entry.path()), testing::slurpFile(other)) << other;
    }
    EXPECT_EQ(csvWithoutTimes(dir / "a" / "results.csv"),
              csvWithoutTimes(dir / "b" / "results.csv"));
    fs::remove_all(dir);
}

// A scene whose texture holds a texel of 3e38 (NaN texels are refused when
// the texture loads): paths over it overflow to infinity, every render
// discards some samples, and both `pathlab render` and the study's cell
// record say how many.
TEST(StudyRecords, NonFiniteSamplesAreCountedPerRenderAndPerCell) {
    const auto dir = testing::scratchDirectory("study-nonfinite");
    testing::usePrivateCache(dir);
    Image texture(2, 2);
    for (float& v : texture.rgb) v = 0.5f;
    texture.rgb[0] = 3e38f;
    writeImage((dir / "nan.pfm").string(), texture);
    std::string scene = testing::slurpFile(PATHLAB_SOURCE_DIR "/scenes/cornell-box.json");
    const std::string white = "\"albedo\": [0.725, 0.71, 0.68]";
    ASSERT_NE(scene.find(white), std::string::npos);
    scene.replace(scene.find(white), white.size(), "\"texture\": \"nan.pfm\"");
    std::ofstream(dir / "nantex.json") << scene;
    const auto spec =
        testing::writeSpec(dir, "n.toml",
                           "name = \"nonfinite\"\nscenes = [\"nantex.json\"]\n"
                           "samplers = [\"halton\", \"independent\"]\nspp = [1, 2]\nseeds = 2\n"
                           "resolution = [16, 16]\n[reference]\nspp = 8\n");
    const auto out = dir / "s";
    const auto r = runPathlab("study " + spec.string() + " -o " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto cells = testing::readCells(out);
    const auto study = studyTable(out);
    ASSERT_EQ(cells.size(), 8u);
    const auto json = nlohmann::json::parse(testing::slurpFile(out / "results.json"));
    for (size_t i = 0; i < cells.size(); ++i) {
        const CellRow& c = cells[i];
        SCOPED_TRACE(c.image);
        EXPECT_GT(c.nonFinite, 0);
        EXPECT_EQ(json.at("cells")[i].at("nonfinite").get<int64_t>(), c.nonFinite);
        // The same render from the command line reports the same count.
        const auto single = runPathlab(renderArgs((dir / "nantex.json").string(), c, study) +
                                           " -o " + (dir / "one.exr").string(),
                                       dir);
        ASSERT_EQ(single.exitCode, 0) << single.err;
        EXPECT_NE(
            single.err.find(", " + std::to_string(c.nonFinite) + " NaN/Inf samples discarded"),
            std::string::npos)
            << single.err;
    }
    EXPECT_NE(testing::slurpFile(out / "results.csv").find("nonfinite"), std::string::npos);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
