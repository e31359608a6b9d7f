// The scene suite: the `suite` and `quick-suite` presets, the difficulty tags
// a spec carries, the public scenes --scenes-dir adds, and the quick suite
// end to end down to the report's verdict page.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <sstream>

#include "core/error.h"
#include "sampling/registry.h"
#include "study/presets.h"
#include "study/suite_presets.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using testing::runPathlab;

std::set<std::string> tagsOf(const StudySpec& spec) {
    std::set<std::string> tags;
    for (const StudyScene& s : spec.scenes) tags.insert(s.difficulty);
    return tags;
}

TEST(SuitePresets, SuiteRunsEverySamplerOnEightScenesOfEveryDifficulty) {
    std::ostringstream log;
    const StudySpec suite = suitePreset(log);
    EXPECT_GE(suite.scenes.size(), 8u) << log.str();
    std::vector<std::string> all;
    for (const SamplerInfo& info : samplerInfos()) all.push_back(info.name);
    EXPECT_EQ(suite.samplers, all);
    EXPECT_EQ(suite.spp, (std::vector<int>{1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024}));
    EXPECT_EQ(suite.seeds, 3);
    for (const StudyScene& s : suite.scenes) {
        EXPECT_FALSE(s.difficulty.empty()) << s.name;
        EXPECT_TRUE(s.source == s.name || fs::is_regular_file(s.source)) << s.source;
    }
    const std::set<std::string> wanted{kDiffuseIndirect, kGlossy,       kRefractive,
                                       kEnvironment,     kDepthOfField, kTextured};
    for (const std::string& tag : wanted) EXPECT_TRUE(tagsOf(suite).count(tag)) << tag;
    // The 200 lights come in their own scene file; while it is absent from
    // the checkout the suite says so and runs without it.
    const bool manyLights =
        fs::is_regular_file(fs::path(PATHLAB_SOURCE_DIR) / "scenes/pbrt/many-lights.pbrt");
    EXPECT_EQ(tagsOf(suite).count(kManyLights), manyLights ? 1u : 0u);
    EXPECT_EQ(log.str().find("many-lights.pbrt") != std::string::npos, !manyLights) << log.str();
}

TEST(SuitePresets, QuickSuiteIsSmallAndTagsEachSceneDifferently) {
    const StudySpec quick = presetSpec("quick-suite");
    EXPECT_GE(quick.scenes.size(), 3u);
    EXPECT_EQ(tagsOf(quick).size(), quick.scenes.size());
    EXPECT_LE(quick.samplers.size(), 4u);
    EXPECT_EQ(quick.resolution.x * quick.resolution.y, 64 * 64);
    EXPECT_LE(quick.spp.back(), 16);
    EXPECT_LE(quick.reference.spp, 256);
    EXPECT_EQ(std::count(quick.samplers.begin(), quick.samplers.end(), "independent"), 1);
}

TEST(SuitePresets, DifficultyTagsSurviveTheResolvedSpecFile) {
    const StudySpec quick = presetSpec("quick-suite");
    const StudySpec again = parseStudySpec(studySpecToToml(quick), "spec.toml", "/");
    ASSERT_EQ(again.scenes.size(), quick.scenes.size());
    for (size_t i = 0; i < quick.scenes.size(); ++i)
        EXPECT_EQ(again.scenes[i].difficulty, quick.scenes[i].difficulty) << quick.scenes[i].name;
    // The tag only labels a scene: a resumed study may change it.
    StudySpec retagged = quick;
    retagged.scenes[0].difficulty = "glossy";
    EXPECT_EQ(firstSpecDifference(quick, retagged), "");
}

TEST(SuitePresets, ADifficultyForNoSceneOfTheStudyIsRefused) {
    const std::string text =
        "scenes = [\"cornell-box\"]\nsamplers = [\"independent\"]\nspp = [1]\n"
        "[difficulty]\ncornell-box = \"diffuse/indirect\"\nwolf = \"glossy\"\n";
    try {
        parseStudySpec(text, "spec.toml", "/");
        FAIL() << "accepted a difficulty for a scene the study does not have";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(),
                     "spec.toml:6: key 'difficulty.wolf' names no scene of the study ('wolf')");
    }
    EXPECT_THROW(parseStudySpec("scenes = [\"cornell-box\"]\nsamplers = [\"independent\"]\n"
                                "spp = [1]\n[difficulty]\ncornell-box = \"\"\n",
                                "spec.toml", "/"),
                 InputError);
}

TEST(SuitePresets, ScenesDirAddsThePublicScenesItHoldsAndNamesTheOthers) {
    const auto dir = testing::scratchDirectory("suite-scenes-dir");
    fs::create_directories(dir / "killeroos");
    fs::copy_file(fs::path(PATHLAB_SOURCE_DIR) / "scenes/pbrt/depth-of-field.pbrt",
                  dir / "killeroos/killeroo-simple.pbrt");
    StudySpec spec = presetSpec("quick-suite");
    const size_t own = spec.scenes.size();
    std::ostringstream log;
    addPublicScenes(spec, dir.string(), log);
    ASSERT_EQ(spec.scenes.size(), own + 1);
    const StudyScene& added = spec.scenes.back();
    EXPECT_EQ(added.name, "killeroo-simple");
    EXPECT_EQ(added.source, (dir / "killeroos/killeroo-simple.pbrt").string());
    EXPECT_EQ(added.difficulty, kGlossy);
    const std::string said = log.str();
    const auto found = said.find("found in"), missing = said.find("not found there");
    ASSERT_NE(found, std::string::npos) << said;
    ASSERT_NE(missing, std::string::npos) << said;
    EXPECT_LT(said.find("killeroos/killeroo-simple.pbrt"), missing) << said;
    EXPECT_GT(said.find("ganesha/ganesha.pbrt"), missing) << said;
    fs::remove_all(dir);
}

TEST(SuiteCli, ScenesDirThatIsNoDirectoryOrWithoutASuiteIsRefused) {
    const auto dir = testing::scratchDirectory("suite-bad-scenes-dir");
    const auto out = dir / "study";
    auto r = runPathlab("study --preset quick-suite --scenes-dir " + (dir / "nowhere").string() +
                            " -o " + out.string(),
                        dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_NE(r.err.find("is not a directory"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    r = runPathlab("study --preset quick --scenes-dir " + dir.string() + " -o " + out.string(),
                   dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_NE(r.err.find("--scenes-dir"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    fs::remove_all(dir);
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

// The quick suite as `make test` runs it: the study, the report, and a
// verdict page with the paragraph and a ranking per scene.
TEST(SuiteCli, QuickSuiteReportHasAVerdictWithARankingPerScene) {
    const auto dir = testing::scratchDirectory("suite-quick");
    testing::usePrivateCache(dir);
    const auto out = dir / "study";
    auto r = runPathlab("study --preset quick-suite -o " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runPathlab("report " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string index = testing::slurpFile(out / "report/index.html");
    EXPECT_NE(index.find("href=\"verdict.html\""), std::string::npos);
    const std::string page = testing::slurpFile(out / "report/verdict.html");
    ASSERT_FALSE(page.empty());
    const StudySpec quick = presetSpec("quick-suite");
    // The overall table, one per difficulty, one per scene.
    EXPECT_EQ(count(page, "<table class=\"ranking\">"), 1 + 2 * quick.scenes.size());
    for (const StudyScene& s : quick.scenes) {
        const auto at = page.find("id=\"scene-" + s.name + "\"");
        ASSERT_NE(at, std::string::npos) << s.name;
        const std::string section = page.substr(at, page.find("<h2", at + 1) - at);
        EXPECT_NE(section.find(s.difficulty), std::string::npos) << s.name;
        EXPECT_EQ(count(section, " spp</th>"), quick.spp.size()) << s.name;
        for (const std::string& sampler : quick.samplers)
            EXPECT_EQ(count(section, "</span>" + sampler + " "), 3 * quick.spp.size())
                << s.name << " " << sampler;
    }
    const auto answer = page.find("id=\"answer\"");
    ASSERT_NE(answer, std::string::npos);
    const std::string paragraph = page.substr(answer, page.find("</p>", answer) - answer);
    EXPECT_NE(paragraph.find("At 16 spp, across the 4 scenes"), std::string::npos) << paragraph;
    EXPECT_NE(paragraph.find("environment-lit scenes"), std::string::npos) << paragraph;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
