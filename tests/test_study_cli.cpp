// `pathlab study` end to end: the quick preset's files and numbers, the
// reference cache, and refusing to overwrite finished work.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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
    // So is a different roulette depth: the reference is another image.
    const auto late =
        testing::writeSpec(dir, "late.toml", testing::tinySpec("roulette_depth = 0\n"));
    const auto fourth = runPathlab("study " + late.string() + " -o " + (dir / "d").string(), dir);
    ASSERT_EQ(fourth.exitCode, 0) << fourth.err;
    EXPECT_NE(fourth.err.find("rendering reference"), std::string::npos) << fourth.err;
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

// Names and contents of every file under `dir`.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> out;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        out[entry.path().string()] =
            entry.is_regular_file() ? testing::slurpFile(entry.path()) : "<directory>";
    return out;
}

// `-o ''` names no directory: it must not mean the current one, whose
// results.csv and spec.toml a study would overwrite.
TEST(StudyCli, EmptyOutputIsRefusedAndTheCurrentDirectoryUntouched) {
    const auto dir = testing::scratchDirectory("study-empty-output");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "tiny.toml", testing::tinySpec());
    std::ofstream(dir / "results.csv") << "someone's results\n";
    const auto before = snapshot(dir);
    const fs::path previous = fs::current_path();
    fs::current_path(dir);
    const auto r = runPathlab("study " + spec.string() + " -o ''", dir);
    fs::current_path(previous);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(r.err, "pathlab: error: -o/--output must name the study directory, got ''\n");
    EXPECT_EQ(snapshot(dir), before);
    fs::remove_all(dir);
}

// A study whose scene file was edited since it began would mix cells of two
// scenes; resuming it is refused like resuming with a changed spec.
TEST(StudyCli, ResumeRefusesAChangedSceneFile) {
    const auto dir = testing::scratchDirectory("study-scene-changed");
    testing::usePrivateCache(dir);
    const std::string scene = R"({"camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
      "materials": {"grey": {"type": "diffuse", "albedo": 0.5}},
      "meshes": [{"material": "grey", "quads": [[[-1,0,-1], [-1,0,1], [1,0,1], [1,0,-1]]]}],
      "lights": [{"type": "quad", "vertices": [[0,3,0], [1,3,0], [1,3,1], [0,3,1]],
                  "emission": EMISSION}]})";
    const auto writeScene = [&](const std::string& emission) {
        std::string text = scene;
        text.replace(text.find("EMISSION"), 8, emission);
        std::ofstream(dir / "box.json") << text;
    };
    writeScene("10");
    const auto spec =
        testing::writeSpec(dir, "box.toml",
                           "scenes = [\"box.json\"]\nsamplers = [\"independent\"]\nspp = [1]\n"
                           "resolution = [8, 8]\n[reference]\nspp = 4\n");
    const auto out = dir / "s";
    const std::string args = "study " + spec.string() + " -o " + out.string() + " --resume";
    ASSERT_EQ(runPathlab(args, dir).exitCode, 0);
    // Unchanged: resumed as before.
    EXPECT_EQ(runPathlab(args, dir).exitCode, 0);

    writeScene("20");
    fs::remove(out / "images/box/independent/spp1-seed0.png");
    const auto before = snapshot(out);
    const auto r = runPathlab(args, dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(r.err, "pathlab: error: '" + out.string() + "' holds a study whose scene 'box' (" +
                         (dir / "box.json").string() +
                         ") has changed since it began: choose another directory\n");
    EXPECT_EQ(snapshot(out), before);
    fs::remove_all(dir);
}

// `halton` unscrambled gives every seed the same image: the study renders it
// once and gives each seed's cell that image and its measurements (the same
// seconds: one render), while a randomised sampler's seeds differ.
TEST(StudyCli, ASamplerTheSeedDoesNotRandomiseIsRenderedOncePerSpp) {
    const auto dir = testing::scratchDirectory("study-deterministic");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(
        dir, "d.toml",
        "scenes = [\"cornell-box\"]\nsamplers = [\"halton\", \"independent\"]\n"
        "spp = [1, 4]\nseeds = 3\nresolution = [16, 16]\n[reference]\nspp = 16\n");
    const auto out = dir / "s";
    const auto r = runPathlab("study " + spec.string() + " -o " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::map<std::pair<std::string, int>, std::vector<CellRow>> bySamplerSpp;
    for (const CellRow& c : testing::readCells(out))
        bySamplerSpp[{c.key.sampler, c.key.spp}].push_back(c);
    ASSERT_EQ(bySamplerSpp.size(), 4u);
    for (const auto& [what, rows] : bySamplerSpp) {
        ASSERT_EQ(rows.size(), 3u);
        for (size_t k = 1; k < rows.size(); ++k) {
            const bool same =
                testing::slurpFile(out / rows[k].image) == testing::slurpFile(out / rows[0].image);
            if (what.first == "halton") {
                EXPECT_TRUE(same) << rows[k].image;
                EXPECT_EQ(rows[k].mse, rows[0].mse);
                EXPECT_EQ(rows[k].flip, rows[0].flip);
                EXPECT_EQ(rows[k].seconds, rows[0].seconds);
            } else {
                EXPECT_FALSE(same) << rows[k].image;
                EXPECT_NE(rows[k].mse, rows[0].mse);
            }
        }
    }
    fs::remove_all(dir);
}

// A run killed after creating results.sqlite but before its first commit
// leaves a database without tables (SQLite creates the file empty); the
// resumed run takes it as a study not yet begun, not as a broken one.
TEST(StudyCli, ResumeTakesADatabaseKilledBeforeItsTables) {
    const auto dir = testing::scratchDirectory("study-empty-database");
    testing::usePrivateCache(dir);
    const auto spec =
        testing::writeSpec(dir, "t.toml",
                           "scenes = [\"cornell-box\"]\nsamplers = [\"independent\"]\nspp = [1]\n"
                           "resolution = [8, 8]\n[reference]\nspp = 4\n");
    const auto out = dir / "s";
    ASSERT_EQ(runPathlab("study " + spec.string() + " -o " + out.string(), dir).exitCode, 0);
    const std::string specToml = testing::slurpFile(out / "spec.toml");
    fs::remove_all(out);
    fs::create_directories(out / "references");
    std::ofstream(out / "spec.toml") << specToml;
    std::ofstream(out / "results.sqlite");  // zero bytes: an empty database
    const auto r = runPathlab("study " + spec.string() + " -o " + out.string() + " --resume", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(testing::readCells(out).size(), 1u);
    fs::remove_all(dir);
}

// Nothing is created when the study is refused after its spec was read: a
// scene that does not load, an impossible thread count.
TEST(StudyCli, RefusedStudyLeavesNoDirectory) {
    const auto dir = testing::scratchDirectory("study-refused");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "tiny.toml", testing::tinySpec());
    const auto r = runPathlab(
        "study " + spec.string() + " -o " + (dir / "s").string() + " --threads 5000", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "s"));
    fs::remove_all(dir);
}

// A file where the report's directory goes is the user's: refused before
// anything is built, and left as it was, with nothing beside it.
TEST(StudyCli, ReportRefusesAFileWhereItsDirectoryGoes) {
    const auto dir = testing::scratchDirectory("study-report-file");
    testing::usePrivateCache(dir);
    const auto spec =
        testing::writeSpec(dir, "t.toml",
                           "scenes = [\"cornell-box\"]\nsamplers = [\"independent\"]\nspp = [1]\n"
                           "resolution = [8, 8]\n[reference]\nspp = 4\n");
    const auto out = dir / "s";
    ASSERT_EQ(runPathlab("study " + spec.string() + " -o " + out.string(), dir).exitCode, 0);
    std::ofstream(out / "report") << "notes\n";
    const auto before = snapshot(out);
    const auto r = runPathlab("report " + out.string(), dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "pathlab: error: '" + (out / "report").string() +
                         "' is not a directory: move it away, the report is written there\n");
    EXPECT_EQ(snapshot(out), before);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
