// `pathlab study` end to end: the quick preset's files and numbers, the
// reference cache, and refusing to overwrite finished work.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/image.h"
#include "study/exports.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using testing::runPathlab;

std::vector<std::string> csvHeader(const fs::path& csv) {
    std::istringstream lines(testing::slurpFile(csv));
    std::string header, name;
    std::getline(lines, header);
    std::vector<std::string> out;
    std::istringstream fields(header);
    while (std::getline(fields, name, ',')) out.push_back(name);
    return out;
}

int csvRows(const fs::path& csv) {
    const std::string text = testing::slurpFile(csv);
    return int(std::count(text.begin(), text.end(), '\n')) - 1;
}

void expectCellImages(const fs::path& dir, const CellRow& c) {
    const Image image = readImage((dir / c.image).string());
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 64);
    if (c.key.seed != 0) return;
    const std::string stem = (dir / c.image).replace_extension("").string();
    for (const char* suffix : {".png", "-flip.png", "-relse.png"}) {
        const Image png = readImage(stem + suffix);
        EXPECT_EQ(png.width, 64) << stem << suffix;
    }
}

TEST(StudyCli, QuickPresetEndToEnd) {
    const auto dir = testing::scratchDirectory("study-quick");
    testing::usePrivateCache(dir);
    const auto out = dir / "study";
    const auto r = runPathlab("study --preset quick -o " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("rendering reference"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("time to target"), std::string::npos) << r.err;  // the summary

    const std::vector<CellRow> cells = testing::readCells(out);
    EXPECT_EQ(cells.size(), 1u * 4 * 5 * 2);  // scenes × samplers × spp × seeds
    for (const CellRow& c : cells) {
        expectCellImages(out, c);
        EXPECT_TRUE(c.relmse && c.flip && c.psnr);
        EXPECT_GT(c.mse, 0);
    }
    EXPECT_EQ(csvHeader(out / "results.csv"), cellColumns());
    for (const char* column :
         {"scene", "sampler", "spp", "seed", "seconds", "mse", "relmse", "flip"})
        EXPECT_NE(std::find(cellColumns().begin(), cellColumns().end(), column),
                  cellColumns().end());
    EXPECT_EQ(csvRows(out / "results.csv"), int(cells.size()));

    const auto results = nlohmann::json::parse(testing::slurpFile(out / "results.json"));
    EXPECT_EQ(results.at("cells").size(), cells.size());
    EXPECT_EQ(results.at("references").size(), 1u);
    EXPECT_EQ(results.at("study").at("name"), "quick");
    const auto analysis = nlohmann::json::parse(testing::slurpFile(out / "analysis.json"));
    EXPECT_EQ(analysis, results.at("analysis"));
    const auto& scene = analysis.at("scenes").at("cornell-box");
    EXPECT_GT(scene.at("noise_floor_mse").get<double>(), 0);
    EXPECT_EQ(scene.at("samplers").size(), 4u);
    EXPECT_EQ(readImage((out / "references/cornell-box.exr").string()).width, 64);
    EXPECT_TRUE(fs::is_regular_file(out / "references/cornell-box.png"));
    EXPECT_TRUE(fs::is_regular_file(out / "spec.toml"));
    fs::remove_all(dir);
}

TEST(StudyCli, MseFallsWithSppForEverySamplerOnTheQuickStudy) {
    const auto dir = testing::scratchDirectory("study-quick-mse");
    testing::usePrivateCache(dir);
    const auto out = dir / "study";
    const auto r = runPathlab("study --preset quick -o " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // Mean MSE over the seeds, per sampler and spp.
    std::map<std::string, std::map<int, double>> mse;
    for (const CellRow& c : testing::readCells(out)) mse[c.key.sampler][c.key.spp] += c.mse / 2;
    ASSERT_EQ(mse.size(), 4u);
    for (const auto& [sampler, curve] : mse) {
        double previous = INFINITY;
        for (const auto& [spp, value] : curve) {
            EXPECT_LT(value, previous) << sampler << " at " << spp << " spp";
            previous = value;
        }
    }
    fs::remove_all(dir);
}

TEST(StudyCli, ReferenceIsRenderedOnceAndReusedFromTheCache) {
    const auto dir = testing::scratchDirectory("study-cache");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "tiny.toml", testing::tinySpec());
    const auto first = runPathlab("study " + spec.string() + " -o " + (dir / "a").string(), dir);
    ASSERT_EQ(first.exitCode, 0) << first.err;
    EXPECT_NE(first.err.find("rendering reference"), std::string::npos) << first.err;
    const auto second = runPathlab("study " + spec.string() + " -o " + (dir / "b").string(), dir);
    ASSERT_EQ(second.exitCode, 0) << second.err;
    EXPECT_EQ(second.err.find("rendering reference"), std::string::npos) << second.err;
    EXPECT_NE(second.err.find("reference: cached"), std::string::npos) << second.err;
    // The same reference, so the same numbers.
    const auto a = testing::readCells(dir / "a"), b = testing::readCells(dir / "b");
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].mse, b[i].mse);
    // A different reference setting is another cache entry.
    const auto other = testing::writeSpec(
        dir, "other.toml",
        testing::tinySpec().replace(testing::tinySpec().find("spp = 256"), 9, "spp = 128"));
    const auto third = runPathlab("study " + other.string() + " -o " + (dir / "c").string(), dir);
    ASSERT_EQ(third.exitCode, 0) << third.err;
    EXPECT_NE(third.err.find("rendering reference"), std::string::npos) << third.err;
    fs::remove_all(dir);
}

TEST(StudyCli, FinishedWorkIsNeverOverwritten) {
    const auto dir = testing::scratchDirectory("study-refuse");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "tiny.toml", testing::tinySpec());
    const std::string args = "study " + spec.string() + " -o " + (dir / "s").string();
    ASSERT_EQ(runPathlab(args, dir).exitCode, 0);
    const auto before = testing::readCells(dir / "s");

    const auto again = runPathlab(args, dir);  // no --resume
    EXPECT_EQ(again.exitCode, 2);
    EXPECT_EQ(again.errLines(), 1) << again.err;
    EXPECT_NE(again.err.find("--resume"), std::string::npos) << again.err;

    const auto resumed = runPathlab(args + " --resume", dir);  // nothing left to do
    EXPECT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_NE(resumed.err.find("0 cells rendered"), std::string::npos) << resumed.err;
    const auto after = testing::readCells(dir / "s");
    ASSERT_EQ(after.size(), before.size());
    for (size_t i = 0; i < after.size(); ++i) EXPECT_EQ(after[i].finishedAt, before[i].finishedAt);

    const auto changed =
        testing::writeSpec(dir, "changed.toml", testing::tinySpec("max_depth = 3\n"));
    const auto other =
        runPathlab("study " + changed.string() + " -o " + (dir / "s").string() + " --resume", dir);
    EXPECT_EQ(other.exitCode, 2);
    EXPECT_NE(other.err.find("max_depth"), std::string::npos) << other.err;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
