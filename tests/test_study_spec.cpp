// Study specs: what a valid one resolves to, and that every mistake is an
// InputError naming the key and its line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "study/presets.h"
#include "study/spec.h"
#include "study_test_util.h"

namespace pathlab {
namespace {

StudySpec parse(const std::string& text) {
    return parseStudySpec(text, "spec.toml", "/tmp");
}

// The message of the InputError parsing `text` throws ("" when it does not).
std::string errorOf(const std::string& text) {
    try {
        parse(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const std::string kValid =
    "scenes = [\"cornell-box\"]\n"          // line 1
    "samplers = [\"halton\", \"sobol\"]\n"  // line 2
    "spp = [16, 1, 4]\n";                   // line 3

TEST(StudySpec, ValidSpecWithDefaults) {
    const StudySpec s = parse(kValid);
    ASSERT_EQ(s.scenes.size(), 1u);
    EXPECT_EQ(s.scenes[0].name, "cornell-box");
    EXPECT_EQ(s.samplers, (std::vector<std::string>{"halton", "sobol"}));
    EXPECT_EQ(s.spp, (std::vector<int>{1, 4, 16}));  // sorted
    EXPECT_EQ(s.seeds, 1);
    EXPECT_EQ(s.resolution.x, 256);
    EXPECT_EQ(s.reference.sampler, "independent");
    EXPECT_EQ(s.reference.seed, kDefaultReferenceSeed);
    EXPECT_FALSE(s.timeBudgetSeconds.has_value());
    EXPECT_TRUE(s.russianRoulette);
    EXPECT_EQ(s.rouletteDepth, 2);
    EXPECT_EQ(parse(kValid + "roulette_depth = 4\n").rouletteDepth, 4);
}

TEST(StudySpec, CanonicalTomlRoundTrips) {
    for (const std::string& name : presetNames()) {
        const StudySpec preset = presetSpec(name);
        const StudySpec again = parse(studySpecToToml(preset));
        EXPECT_EQ(firstSpecDifference(preset, again), "") << name;
    }
    StudySpec changed = presetSpec("quick");
    changed.reference.spp *= 2;
    EXPECT_EQ(firstSpecDifference(presetSpec("quick"), changed), "reference.spp");
    changed = presetSpec("quick");
    changed.rouletteDepth = 4;
    EXPECT_EQ(firstSpecDifference(presetSpec("quick"), changed), "roulette_depth");
    changed = presetSpec("quick");
    changed.reference.ranges = 32;
    EXPECT_EQ(firstSpecDifference(presetSpec("quick"), changed), "reference.ranges");
    EXPECT_EQ(parse(studySpecToToml(changed)).reference.ranges, 32);
}

// Names may hold any character TOML can escape; the canonical TOML must read
// back (a raw DEL, which JSON-style escaping leaves alone, is not valid TOML).
TEST(StudySpec, CanonicalTomlEscapesControlCharacters) {
    StudySpec s = parse(kValid);
    s.name = std::string("tab\t del\x7f nul") + '\0' + "\x1f \"quoted\" \\ é";
    const StudySpec again = parse(studySpecToToml(s));
    EXPECT_EQ(again.name, s.name);
    EXPECT_EQ(firstSpecDifference(s, again), "");
}

TEST(StudySpec, ErrorsNameTheKeyAndTheLine) {
    struct Case {
        std::string text, expected;
    };
    const std::vector<Case> cases = {
        {kValid + "samplerz = [\"halton\"]\n", "spec.toml:4: key 'samplerz' is not"},
        {kValid + "seeds = \"three\"\n", "spec.toml:4: key 'seeds' must be an integer, got string"},
        {kValid + "seeds = 0\n", "spec.toml:4: key 'seeds' must be between 1"},
        {kValid + "roulette_depth = -1\n", "spec.toml:4: key 'roulette_depth' must be between 0"},
        {"scenes = [\"cornell-box\"]\nsamplers = [\"halton\",\n  \"nope\"]\nspp = [1]\n",
         "spec.toml:3: key 'samplers[1]' names an unknown sampler 'nope'"},
        {"scenes = [\"no-such-scene\"]\nsamplers = [\"halton\"]\nspp = [1]\n",
         "spec.toml:1: key 'scenes[0]' names 'no-such-scene'"},
        {"scenes = [\"cornell-box\"]\nsamplers = [\"halton\"]\nspp = [1, 0]\n",
         "spec.toml:3: key 'spp[1]' must be between 1"},
        {"scenes = [\"cornell-box\"]\nsamplers = [\"halton\"]\nspp = [4, -2]\n",
         "spec.toml:3: key 'spp[1]' must be between 1"},
        {kValid + "[reference]\nspp = 1.5\n",
         "spec.toml:5: key 'reference.spp' must be an integer"},
        {kValid + "[reference]\nsampler = \"x\"\n", "spec.toml:5: key 'reference.sampler'"},
        {kValid + "[reference]\nspp = 64\ncolour = 1\n", "spec.toml:6: key 'reference.colour'"},
        {kValid + "[reference]\nspp = 64\nranges = 0\n",
         "spec.toml:6: key 'reference.ranges' must be between 1 and 4096"},
        {kValid + "[reference]\nspp = 64\nranges = 65\n",
         "spec.toml:6: key 'reference.ranges' must be at most reference.spp (64)"},
        {kValid + "resolution = [64]\n", "spec.toml:4: key 'resolution' must be [width, height]"},
        {kValid + "time_budget_seconds = -1\n", "spec.toml:4: key 'time_budget_seconds'"},
        {kValid + "metrics = [\"mse\", \"ssim\"]\n", "spec.toml:4: key 'metrics[1]'"},
        {"scenes = [\"cornell-box\"]\nspp = [1]\n", "key 'samplers' is missing"},
        {kValid + "seeds = = 2\n", "spec.toml:4:"},
    };
    for (const Case& c : cases) {
        const std::string message = errorOf(c.text);
        EXPECT_NE(message.find(c.expected), std::string::npos)
            << "spec:\n"
            << c.text << "message: " << message << "\nexpected: " << c.expected;
    }
}

// The commented example is the seed preset written out (docs/study.md gives
// its measured time for both).
TEST(StudySpec, DocumentedExampleIsTheSeedPreset) {
    const StudySpec s = loadStudySpec(PATHLAB_SOURCE_DIR "/docs/study-spec.toml");
    const StudySpec seed = presetSpec("seed");
    ASSERT_EQ(s.scenes.size(), seed.scenes.size());
    for (size_t i = 0; i < s.scenes.size(); ++i) EXPECT_EQ(s.scenes[i].name, seed.scenes[i].name);
    EXPECT_EQ(s.samplers, seed.samplers);
    EXPECT_EQ(s.spp, seed.spp);
    EXPECT_EQ(s.seeds, seed.seeds);
    EXPECT_EQ(s.resolution.x, seed.resolution.x);
    EXPECT_EQ(s.resolution.y, seed.resolution.y);
    EXPECT_EQ(s.maxDepth, seed.maxDepth);
    EXPECT_EQ(s.russianRoulette, seed.russianRoulette);
    EXPECT_EQ(s.rouletteDepth, seed.rouletteDepth);
    EXPECT_EQ(s.reference.spp, seed.reference.spp);
    EXPECT_EQ(s.reference.sampler, seed.reference.sampler);
    EXPECT_EQ(s.timeBudgetSeconds, seed.timeBudgetSeconds);
    EXPECT_EQ(seed.resolution.x, 256);
    EXPECT_EQ(seed.reference.spp, 4096);
}

TEST(StudySpec, RelativeSceneFilesResolveAgainstTheSpec) {
    const auto dir = testing::scratchDirectory("study-spec-scene");
    std::ofstream(dir / "box.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    testing::writeSpec(dir, "s.toml",
                       "scenes = [\"box.obj\"]\nsamplers = [\"halton\"]\nspp = [1]\n");
    const StudySpec s = loadStudySpec((dir / "s.toml").string());
    EXPECT_EQ(s.scenes[0].name, "box");
    EXPECT_EQ(s.scenes[0].source, (dir / "box.obj").string());
    std::filesystem::remove_all(dir);
}

TEST(StudyCli, MalformedSpecExitsWithOneLineNamingKeyAndLine) {
    const auto dir = testing::scratchDirectory("study-cli-malformed");
    const auto spec = testing::writeSpec(
        dir, "bad.toml",
        "scenes = [\"cornell-box\"]\nsamplers = [\"halton\"]\nspp = [1, 2]\nseedz = 3\n");
    const auto r =
        testing::runPathlab("study " + spec.string() + " -o " + (dir / "out").string(), dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_NE(r.err.find("bad.toml:4: key 'seedz'"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "results.sqlite"));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
