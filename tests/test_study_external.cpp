// Another renderer's images in a study ([[external]]): measured exactly as the
// study's own cells, skipped on --resume while unchanged, and refused with one
// line when they cannot be used.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using testing::runPathlab;

// Two samplers, two spp, two seeds of the Cornell box at 32×32.
std::string ownSpec(const std::string& extra = "") {
    return "name = \"external\"\n"
           "scenes = [\"cornell-box\"]\n"
           "samplers = [\"sobol-owen\", \"independent\"]\n"
           "spp = [1, 4]\n"
           "seeds = 2\n"
           "resolution = [32, 32]\n"
           "[reference]\n"
           "spp = 256\n" +
           extra;
}

std::string externalTable(const std::string& name, const std::string& images,
                          const std::string& more = "") {
    return "[[external]]\nname = \"" + name + "\"\nscene = \"cornell-box\"\nimages = \"" + images +
           "\"\n" + more;
}

class StudyExternal : public ::testing::Test {
  protected:
    fs::path dir;
    void SetUp() override {
        dir = testing::scratchDirectory(
            std::string("study-external-") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        testing::usePrivateCache(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    testing::CliResult study(const std::string& spec, const fs::path& out, bool resume = false) {
        const auto path = testing::writeSpec(dir, "spec.toml", spec);
        return runPathlab(
            "study " + path.string() + " -o " + out.string() + (resume ? " --resume" : ""), dir);
    }
    // The study's own images, as another renderer would have left them.
    std::string ownImages(const fs::path& out) const {
        return (out / "images/cornell-box/{sampler}/spp{spp}-seed{seed}.exr").string();
    }
};

std::map<CellKey, CellRow> byKey(const std::vector<CellRow>& cells) {
    std::map<CellKey, CellRow> out;
    for (const CellRow& c : cells) out[c.key] = c;
    return out;
}

TEST_F(StudyExternal, OwnImagesFedBackMeasureExactlyTheSame) {
    const fs::path first = dir / "first", second = dir / "second";
    ASSERT_EQ(study(ownSpec(), first).exitCode, 0);
    const auto r = study(ownSpec(externalTable("again", ownImages(first))), second);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto cells = byKey(testing::readCells(second));
    ASSERT_EQ(cells.size(), 16u);  // 8 own cells, 8 external
    for (const auto& [key, own] : cells) {
        if (key.sampler.find(':') != std::string::npos) continue;
        const auto again = cells.find({key.scene, "again:" + key.sampler, key.spp, key.seed});
        ASSERT_NE(again, cells.end()) << key.sampler;
        const CellRow& e = again->second;
        EXPECT_EQ(e.mse, own.mse);
        EXPECT_EQ(e.rmse, own.rmse);
        EXPECT_EQ(e.relmse, own.relmse);
        EXPECT_EQ(e.flip, own.flip);
        EXPECT_EQ(e.flipMedian, own.flipMedian);
        EXPECT_EQ(e.psnr, own.psnr);
        EXPECT_EQ(e.bias, own.bias);
        ASSERT_TRUE(e.mseEdge && e.mseRest);  // the scene is known: the regions too
        EXPECT_EQ(e.mseEdge, own.mseEdge);
        EXPECT_EQ(e.mseRest, own.mseRest);
        EXPECT_FALSE(e.sourceHash.empty());
        EXPECT_TRUE(own.sourceHash.empty());
        EXPECT_EQ(fs::path(e.image), first / own.image);
        if (key.seed != 0) continue;
        const std::string stem =
            "images/cornell-box/again:" + key.sampler + "/spp" + std::to_string(key.spp) + "-seed0";
        for (const char* suffix : {".png", "-flip.png", "-relse.png"})
            EXPECT_TRUE(fs::is_regular_file(second / (stem + suffix))) << stem << suffix;
    }
    // The analysis and the exports treat them as samplers of the scene.
    const auto analysis = nlohmann::json::parse(testing::slurpFile(second / "analysis.json"));
    EXPECT_TRUE(analysis["scenes"]["cornell-box"]["samplers"].contains("again:sobol-owen"));
    EXPECT_NE(testing::slurpFile(second / "bias.csv").find("cornell-box,again:independent,4,2,"),
              std::string::npos);
}

TEST_F(StudyExternal, ResumeMeasuresOnlyChangedFiles) {
    const fs::path first = dir / "first", second = dir / "second";
    ASSERT_EQ(study(ownSpec(), first).exitCode, 0);
    // The renders kept apart, so one can be changed.
    const fs::path renders = dir / "renders";
    fs::copy(first / "images/cornell-box", renders, fs::copy_options::recursive);
    const std::string spec =
        ownSpec(externalTable("copy", (renders / "{sampler}/spp{spp}-seed{seed}.exr").string()));
    ASSERT_EQ(study(spec, second).exitCode, 0);
    const auto before = byKey(testing::readCells(second));
    const auto again = study(spec, second, true);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(again.err.find("0 cells rendered, 16 already done"), std::string::npos) << again.err;
    // One file rewritten brighter: that cell, and only it, is measured again.
    const fs::path changed = renders / "independent/spp4-seed1.exr";
    Image image = readImage(changed.string());
    for (float& v : image.rgb) v *= 1.05f;
    writeImage(changed.string(), image);
    const auto third = study(spec, second, true);
    ASSERT_EQ(third.exitCode, 0) << third.err;
    EXPECT_NE(third.err.find("1 cells rendered, 15 already done"), std::string::npos) << third.err;
    const auto after = byKey(testing::readCells(second));
    for (const auto& [key, row] : after) {
        const bool isChanged = key.sampler == "copy:independent" && key.spp == 4 && key.seed == 1;
        const CellRow& old = before.at(key);
        if (isChanged) {
            EXPECT_NE(row.mse, old.mse);
            EXPECT_NEAR(*row.bias, 1.05 * (1 + *old.bias) - 1, 1e-6);
        } else {
            EXPECT_EQ(row.finishedAt, old.finishedAt) << key.sampler;
            EXPECT_EQ(row.mse, old.mse) << key.sampler;
        }
    }
}

TEST_F(StudyExternal, BadTablesGiveOneLineAndExit2BeforeWriting) {
    const fs::path first = dir / "first";
    ASSERT_EQ(study(ownSpec(), first).exitCode, 0);
    const fs::path renders = dir / "renders";
    fs::copy(first / "images/cornell-box", renders, fs::copy_options::recursive);
    const std::string pattern = (renders / "{sampler}/spp{spp}-seed{seed}.exr").string();
    fs::create_directories(dir / "small/independent");
    writeImage((dir / "small/independent/spp1-seed0.exr").string(), Image(16, 16));
    fs::create_directories(dir / "broken/independent");
    std::ofstream(dir / "broken/independent/spp1-seed0.exr") << "not an image";
    fs::create_directories(dir / "holes/independent");
    fs::copy(renders / "independent/spp1-seed0.exr", dir / "holes/independent/spp1-seed0.exr");
    fs::copy(renders / "independent/spp4-seed1.exr", dir / "holes/independent/spp4-seed1.exr");
    struct Case {
        std::string table, expected;
    };
    const std::vector<Case> cases = {
        {externalTable("none", (dir / "nowhere/{sampler}-{spp}-{seed}.exr").string()),
         "matches no file"},
        {externalTable("halton", pattern), "is the name of a pathlab sampler"},
        {externalTable("x", (renders / "{sampler}/spp{spp}.exr").string()),
         "{sampler}, {spp} and {seed}"},
        {externalTable("small", (dir / "small/{sampler}/spp{spp}-seed{seed}.exr").string()),
         "is 16x16"},
        {externalTable("broken", (dir / "broken/{sampler}/spp{spp}-seed{seed}.exr").string()),
         "cannot read EXR"},
        {externalTable("holes", (dir / "holes/{sampler}/spp{spp}-seed{seed}.exr").string()),
         "missing image"},
        {externalTable("t", pattern, "times = \"" + (dir / "no-times.csv").string() + "\"\n"),
         "no-times.csv"},
        {"[[external]]\nname = \"other\"\nscene = \"kitchen\"\nimages = \"" + pattern + "\"\n",
         "not a scene of the study"},
    };
    for (const Case& c : cases) {
        const fs::path out = dir / "bad";
        const auto r = study(ownSpec(c.table), out);
        EXPECT_EQ(r.exitCode, 2) << c.table;
        EXPECT_EQ(r.errLines(), 1) << r.err;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out)) << c.table;
    }
}

TEST_F(StudyExternal, SceneThePathlabCannotRenderWithItsOwnReference) {
    const fs::path first = dir / "first", second = dir / "second";
    ASSERT_EQ(study(ownSpec(), first).exitCode, 0);
    const std::string table =
        "[[external]]\nname = \"other\"\nscene = \"their-scene\"\nimages = \"" + ownImages(first) +
        "\"\nreference = \"" + (first / "references/cornell-box.exr").string() + "\"\n";
    const auto r = study(ownSpec(table), second);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto cells = byKey(testing::readCells(second));
    const CellRow& own = cells.at({"cornell-box", "independent", 4, 1});
    const CellRow& other = cells.at({"their-scene", "other:independent", 4, 1});
    // The same reference image: the same numbers, without the regions.
    EXPECT_EQ(other.mse, own.mse);
    EXPECT_EQ(other.flip, own.flip);
    EXPECT_FALSE(other.mseEdge.has_value());
    EXPECT_TRUE(fs::is_regular_file(second / "references/their-scene.png"));
}

}  // namespace
}  // namespace pathlab
