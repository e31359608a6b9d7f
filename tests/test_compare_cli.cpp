// `pathlab compare` end to end: output formats, mode selection and errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.h"
#include "core/image.h"
#include "metrics/error_spectrum.h"
#include "metrics/image_metrics.h"
#include "render/emitter_edges.h"
#include "scene/builtin_scenes.h"

namespace pathlab {
namespace {

namespace fs = std::filesystem;

using testing::CliResult;
using testing::runPathlab;

class CompareCli : public ::testing::Test {
  protected:
    fs::path dir;

    void SetUp() override {
        dir = fs::temp_directory_path() /
              ("pathlab_compare_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::string path(const std::string& name) const { return (dir / name).string(); }

    CliResult run(const std::string& args) const { return runPathlab("compare " + args, dir); }

    // A small image with some structure; `offset` changes it a little.
    std::string writePattern(const std::string& name, int w, int h, float offset,
                             float scale = 1.0f) const {
        Image img(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float v = ((x / 4 + y / 4) % 2 ? 0.7f : 0.2f) + 0.02f * float(x % 5) +
                                offset * float((x * y) % 3);
                img.set(x, y, Vec3f(v * scale, 0.5f * v * scale, 0.3f * scale));
            }
        writeImage(path(name), img);
        return path(name);
    }
};

int countLines(const std::string& s) {
    return int(std::count(s.begin(), s.end(), '\n'));
}

TEST_F(CompareCli, JsonForPngPairHasEveryMetricInLdrMode) {
    const std::string a = writePattern("a.png", 32, 24, 0.0f),
                      b = writePattern("b.png", 32, 24, 0.05f);
    const CliResult r = run(a + " " + b + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"mse", "rmse", "relmse", "psnr"})
        EXPECT_GT(j[key].get<double>(), 0) << key;
    // b is a brighter than a where (x·y) mod 3 > 0.
    EXPECT_GT(j["bias"]["mean"].get<double>(), 0);
    EXPECT_EQ(j["relmse_epsilon"].get<double>(), 0.01);
    const auto& f = j["flip"];
    EXPECT_EQ(f["mode"], "ldr");
    EXPECT_NEAR(f["ppd"].get<double>(), 67.02, 0.01);
    EXPECT_GT(f["mean"].get<double>(), 0);
    EXPECT_LE(f["min"].get<double>(), f["q1"].get<double>());
    EXPECT_LE(f["q1"].get<double>(), f["weighted_median"].get<double>());
    EXPECT_LE(f["weighted_median"].get<double>(), f["q3"].get<double>());
    EXPECT_LE(f["q3"].get<double>(), f["max"].get<double>());
    EXPECT_TRUE(f["exposures"].is_null());
}

TEST_F(CompareCli, JsonForExrPairIsHdrWithExposureRange) {
    const std::string a = writePattern("a.exr", 32, 24, 0.0f, 8.0f);
    const std::string b = writePattern("b.exr", 32, 24, 0.05f, 8.0f);
    const CliResult r = run(a + " " + b + " --json --metric flip");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_FALSE(j.contains("mse"));
    EXPECT_EQ(j["flip"]["mode"], "hdr");
    const auto& e = j["flip"]["exposures"];
    EXPECT_LT(e["start"].get<double>(), e["stop"].get<double>());
    EXPECT_GE(e["count"].get<int>(), 2);
}

TEST_F(CompareCli, ModeCanBeOverridden) {
    const std::string a = writePattern("a.exr", 16, 16, 0.0f),
                      b = writePattern("b.exr", 16, 16, 0.1f);
    EXPECT_EQ(nlohmann::json::parse(run(a + " " + b + " --json --ldr").out)["flip"]["mode"], "ldr");
    const std::string c = writePattern("c.png", 16, 16, 0.0f),
                      d = writePattern("d.png", 16, 16, 0.1f);
    EXPECT_EQ(nlohmann::json::parse(run(c + " " + d + " --json --hdr").out)["flip"]["mode"], "hdr");
    EXPECT_EQ(run(c + " " + d + " --ldr --hdr").exitCode, 2);
}

TEST_F(CompareCli, SingleMetricAndIdenticalImages) {
    const std::string a = writePattern("a.png", 16, 16, 0.0f);
    const CliResult r = run(a + " " + a + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["mse"].get<double>(), 0.0);
    EXPECT_EQ(j["relmse"].get<double>(), 0.0);
    EXPECT_TRUE(j["psnr"].is_null());  // infinite
    EXPECT_EQ(j["bias"]["relative"].get<double>(), 0.0);
    EXPECT_EQ(j["flip"]["mean"].get<double>(), 0.0);
    const auto only = nlohmann::json::parse(run(a + " " + a + " --json --metric relmse").out);
    EXPECT_TRUE(only.contains("relmse") && only.contains("relmse_epsilon"));
    EXPECT_FALSE(only.contains("mse") || only.contains("flip") || only.contains("psnr"));
}

// A copy scaled by 1.05 is 5% too bright everywhere: its bias is 0.05 of
// the reference's mean in total and per channel, and its sign says brighter.
TEST_F(CompareCli, ScaledCopyHasRelativeBiasOfItsScale) {
    const std::string a = writePattern("a.exr", 32, 24, 0.03f);
    Image scaled = readImage(a);
    double sum = 0;
    std::array<double, 3> channel{};
    for (size_t i = 0; i < scaled.rgb.size(); ++i) {
        sum += scaled.rgb[i];
        channel[i % 3] += scaled.rgb[i];
        scaled.rgb[i] *= 1.05f;
    }
    writeImage(path("b.exr"), scaled);
    const CliResult r = run(a + " " + path("b.exr") + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto bias = nlohmann::json::parse(r.out).at("bias");
    const double pixels = 32.0 * 24.0;
    EXPECT_NEAR(bias.at("relative").get<double>(), 0.05, 1e-6);
    EXPECT_NEAR(bias.at("mean").get<double>(), 0.05 * sum / (3 * pixels), 1e-6);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(bias.at("channels")[c].get<double>(), 0.05 * channel[size_t(c)] / pixels, 1e-6);
    // Swapped, the reference is the brighter one: the sign turns, and the
    // relative value is against the brighter mean (−0.05 / 1.05).
    const auto back = nlohmann::json::parse(run(path("b.exr") + " " + a + " --json").out);
    EXPECT_NEAR(back.at("bias").at("relative").get<double>(), -0.05 / 1.05, 1e-6);
}

TEST_F(CompareCli, TextOutputIsAFewReadableLines) {
    const std::string a = writePattern("a.png", 16, 16, 0.0f),
                      b = writePattern("b.png", 16, 16, 0.1f);
    const CliResult r = run(a + " " + b);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("mse"), std::string::npos);
    EXPECT_NE(r.out.find("psnr"), std::string::npos);
    EXPECT_NE(r.out.find("flip    mean"), std::string::npos);
    EXPECT_LE(countLines(r.out), 8);
}

TEST_F(CompareCli, WritesMagmaErrorMap) {
    const std::string a = writePattern("a.png", 20, 12, 0.0f),
                      b = writePattern("b.png", 20, 12, 0.1f);
    const CliResult r = run(a + " " + b + " --metric flip --error-map " + path("map.png"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image map = readImage(path("map.png"));
    EXPECT_EQ(map.width, 20);
    EXPECT_EQ(map.height, 12);
    // Identical images: every pixel is magma's first (near-black) entry.
    ASSERT_EQ(run(a + " " + a + " --error-map " + path("zero.png")).exitCode, 0);
    const Image zero = readImage(path("zero.png"));
    for (float v : zero.rgb) EXPECT_LT(v, 0.002f);
}

TEST_F(CompareCli, DifferentSizesFailWithOneLineAndNoMap) {
    const std::string a = writePattern("a.png", 16, 16, 0.0f),
                      b = writePattern("b.png", 16, 12, 0.0f);
    const CliResult r = run(a + " " + b + " --error-map " + path("map.png"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("16x12"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
    EXPECT_FALSE(fs::exists(path("map.png")));
}

TEST_F(CompareCli, UnreadableFilesFail) {
    const std::string a = writePattern("a.png", 8, 8, 0.0f);
    CliResult r = run(a + " " + path("missing.png"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("missing.png"), std::string::npos);
    std::ofstream(path("junk.png")) << "not a png";
    r = run(a + " " + path("junk.png"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
}

TEST_F(CompareCli, NonFinitePixelsAreCountedAndRejected) {
    Image img(8, 8);
    img.rgb[0] = std::numeric_limits<float>::quiet_NaN();
    img.rgb[30] = std::numeric_limits<float>::infinity();
    img.rgb[31] = std::numeric_limits<float>::quiet_NaN();  // same pixel as 30
    writeImage(path("bad.exr"), img);
    writeImage(path("good.exr"), Image(8, 8));
    const CliResult r =
        run(path("good.exr") + " " + path("bad.exr") + " --error-map " + path("m.png"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("2 of 64"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("m.png")));
}

TEST_F(CompareCli, UnwritableErrorMapFailsBeforeWorkAndLeavesNothing) {
    const std::string a = writePattern("a.png", 8, 8, 0.0f), b = writePattern("b.png", 8, 8, 0.1f);
    const CliResult r = run(a + " " + b + " --error-map " + path("no/such/dir/map.png"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
    EXPECT_EQ(run(a + " " + b + " --error-map " + path("map.jpg")).exitCode, 2);
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        EXPECT_TRUE(name == "a.png" || name == "b.png" || name == "stdout.txt" ||
                    name == "stderr.txt")
            << "unexpected file " << name;
    }
}

// --regions SCENE: the MSE over the pixels where the scene's light has its
// outline (framed at the images' size) and elsewhere, as the study reports it.
TEST_F(CompareCli, RegionsSplitTheMseByTheScenesEmitterEdge) {
    const std::string a = writePattern("a.exr", 40, 30, 0.0f),
                      b = writePattern("b.exr", 40, 30, 0.05f);
    const CliResult r = run(a + " " + b + " --metric mse --json --regions cornell-box");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const auto mask = emitterEdgePixels(RenderScene(cornellBoxScene()), {40, 30});
    const RegionMse expected = meanSquaredErrorByRegion(readImage(a), readImage(b), mask);
    ASSERT_GT(expected.insidePixels, 0u);
    EXPECT_EQ(j["regions"]["edge_pixels"].get<size_t>(), expected.insidePixels);
    EXPECT_DOUBLE_EQ(j["regions"]["mse_edge"].get<double>(), *expected.inside);
    EXPECT_DOUBLE_EQ(j["regions"]["mse_rest"].get<double>(), *expected.outside);
    EXPECT_EQ(j["regions"]["scene"], "cornell-box");
    const CliResult text = run(a + " " + b + " --metric mse --regions cornell-box");
    EXPECT_NE(text.out.find("emitter-edge pixels of cornell-box"), std::string::npos) << text.out;
    const CliResult bad = run(a + " " + b + " --regions no-such-scene");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_EQ(countLines(bad.err), 1) << bad.err;
    EXPECT_TRUE(bad.out.empty());
}

// --error-spectrum writes errorSpectrum of the two files as CSV (bit for bit)
// or as a plot; --json gains its low-frequency fraction.
TEST_F(CompareCli, ErrorSpectrumAsCsvPngAndJson) {
    const std::string a = writePattern("a.exr", 40, 30, 0.0f),
                      b = writePattern("b.exr", 40, 30, 0.05f);
    const CliResult r = run(a + " " + b + " --json --error-spectrum " + path("s.csv"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const RadialPowerSpectrum expected = errorSpectrum(readImage(a), readImage(b));
    EXPECT_EQ(testing::slurpFile(path("s.csv")), errorSpectrumCsv(expected));
    EXPECT_EQ(expected.power.size(), 16u);  // rings 0..30/2
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["low_frequency_fraction"].get<double>(), expected.lowFrequencyFraction());
    ASSERT_EQ(run(a + " " + b + " --metric mse --error-spectrum " + path("s.PNG")).exitCode, 0);
    const Image plot = readImage(path("s.PNG"));
    EXPECT_EQ(plot.width, 480);
    EXPECT_EQ(plot.height, 320);
    // Identical images: no error power, the fraction is null.
    const auto same = nlohmann::json::parse(run(a + " " + a + " --json").out);
    EXPECT_TRUE(same["low_frequency_fraction"].is_null());
}

TEST_F(CompareCli, ErrorSpectrumTargetIsCheckedBeforeTheWork) {
    const std::string a = writePattern("a.exr", 8, 8, 0.0f);
    for (const std::string& target : {path("s.txt"), path("missing/s.csv"), path("s")}) {
        const CliResult r = run(a + " " + a + " --error-spectrum " + target);
        EXPECT_EQ(r.exitCode, 2) << target;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(target), std::string::npos) << r.err;
        EXPECT_TRUE(r.out.empty());
        EXPECT_FALSE(fs::exists(target));
    }
}

TEST_F(CompareCli, BadMetricIsAUsageError) {
    const std::string a = writePattern("a.png", 8, 8, 0.0f);
    const CliResult r = run(a + " " + a + " --metric ssim");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
}

}  // namespace
}  // namespace pathlab
