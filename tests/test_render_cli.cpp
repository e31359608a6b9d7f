// `pathlab render` from the outside: output types, bad input (one line, exit
// code 2, no partial file), and identical bytes whatever the thread count.
#include <gtest/gtest.h>
#include <unistd.h>

#include "cli_runner.h"
#include "core/image.h"

namespace pathlab {
namespace {

using testing::runPathlab;

class RenderCli : public ::testing::Test {
  protected:
    void SetUp() override { dir = testing::scratchDirectory("render"); }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    // The directory holds nothing but what the command was asked to write.
    bool directoryEmpty() const { return std::filesystem::is_empty(dir); }
    std::filesystem::path dir;
};

TEST_F(RenderCli, WritesExrAndPngOfTheCornellBox) {
    for (const char* name : {"cb.exr", "cb.png"}) {
        const auto r =
            runPathlab("render --scene cornell-box --spp 4 --size 32x24 -o " + path(name), dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Image img = readImage(path(name));
        EXPECT_EQ(img.width, 32);
        EXPECT_EQ(img.height, 24);
        // The summary line reports time and throughput.
        EXPECT_NE(r.err.find("paths/s"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("rays/s"), std::string::npos) << r.err;
    }
}

TEST_F(RenderCli, IdenticalBytesForOneTwoAndEightThreads) {
    std::string first;
    for (int threads : {1, 2, 8}) {
        const std::string out = path(std::to_string(threads) + "-threads.exr");
        const auto r = runPathlab(
            "render --scene cornell-box --spp 8 --size 48x40 --seed 3 "
            "--threads " +
                std::to_string(threads) + " -o " + out,
            dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const std::string bytes = testing::slurpFile(out);
        if (first.empty()) first = bytes;
        EXPECT_EQ(bytes, first) << threads << " threads";
    }
}

// Roulette that may start only at the maximum depth never fires: the same
// bytes as no roulette. An earlier start is a different image.
TEST_F(RenderCli, RouletteDepthReachesTheRenderer) {
    const std::string common = "render --scene cornell-box --spp 4 --size 32x24 --max-depth 4 ";
    const auto render = [&](const std::string& args, const std::string& name) {
        const auto r = runPathlab(common + args + " -o " + path(name), dir);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return testing::slurpFile(path(name));
    };
    const std::string none = render("--no-russian-roulette", "none.exr");
    EXPECT_EQ(render("--roulette-depth 4", "late.exr"), none);
    EXPECT_NE(render("--roulette-depth 0", "early.exr"), none);
    EXPECT_NE(render("", "default.exr"), none);
}

struct BadInput {
    const char* args;
    const char* mentions;  // a word the one-line message must contain
};

TEST_F(RenderCli, BadInputIsOneLineAndExitCodeTwo) {
    std::ofstream(path("broken.json")) << "{ \"camera\": { \"eye\": [0, 0, ";
    const BadInput cases[] = {
        {"--scene no-such-scene.json --spp 1", "no-such-scene"},
        {"--scene BROKEN --spp 1", "broken.json"},
        {"--scene cornell-box --spp 1 --sampler nonsense", "nonsense"},
        {"--scene cornell-box --spp 0", "spp"},
        {"--scene cornell-box --spp 1 --size 0x0", "size"},
        {"--scene cornell-box --spp 1 --size huge", "size"},
        {"--scene cornell-box --spp 1 --max-depth -3", "depth"},
        {"--scene cornell-box --spp 1 --roulette-depth -1", "--roulette-depth"},
        {"--scene cornell-box --spp -5", "spp"},
    };
    for (const BadInput& c : cases) {
        std::string args = c.args;
        if (auto at = args.find("BROKEN"); at != std::string::npos)
            args.replace(at, 6, path("broken.json"));
        const auto r = runPathlab("render " + args + " -o " + path("out.png"), dir);
        EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
        EXPECT_EQ(r.errLines(), 1) << args << ": " << r.err;
        EXPECT_NE(r.err.find(c.mentions), std::string::npos) << args << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(path("out.png"))) << args;
    }
}

TEST_F(RenderCli, UnwritableOutputFailsBeforeRendering) {
    const auto r =
        runPathlab("render --scene cornell-box --spp 1 -o " + path("missing/dir/x.png"), dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.errLines(), 1) << r.err;
    const auto r2 = runPathlab("render --scene cornell-box --spp 1 -o " + path("x.tiff"), dir);
    EXPECT_EQ(r2.exitCode, 2);
    EXPECT_NE(r2.err.find(".tiff"), std::string::npos) << r2.err;
    if (::geteuid() != 0) {  // root ignores directory permissions
        std::filesystem::create_directory(dir / "ro");
        std::filesystem::permissions(
            dir / "ro", std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
        const auto r3 =
            runPathlab("render --scene cornell-box --spp 1 -o " + path("ro/x.png"), dir);
        EXPECT_EQ(r3.exitCode, 2);
    }
}

TEST_F(RenderCli, ExistingOutputSurvivesAFailedRun) {
    const std::string out = path("keep.png");
    ASSERT_EQ(runPathlab("render --scene cornell-box --spp 1 --size 8x8 -o " + out, dir).exitCode,
              0);
    const std::string before = testing::slurpFile(out);
    EXPECT_EQ(runPathlab("render --scene cornell-box --spp 0 -o " + out, dir).exitCode, 2);
    EXPECT_EQ(testing::slurpFile(out), before);
}

}  // namespace
}  // namespace pathlab
