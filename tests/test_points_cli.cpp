// `pathlab samplers` and `pathlab points` from the outside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

struct Result {
    int exitCode;
    std::string out;
};

Result run(const std::string& args) {
    const std::string command = std::string(PATHLAB_BINARY) + " " + args + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    std::string out;
    char buffer[4096];
    while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "pathlab-points-cli";
    fs::create_directories(dir);
    fs::remove(dir / name);
    return dir / name;
}

TEST(SamplersCli, ListsEverySamplerWithDimensionsAndRandomization) {
    const Result r = run("samplers");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    std::istringstream lines(r.out);
    std::string line, names;
    std::getline(lines, line);  // header
    while (std::getline(lines, line)) names += line.substr(0, line.find(' ')) + " ";
    EXPECT_EQ(
        names,
        "standard halton halton-rd halton-owen blue-noise independent stratified sobol "
        "sobol-xor sobol-global-owen sobol-owen zsobol sobol-bluenoise pmj02 cascaded-sobol ");
    EXPECT_NE(r.out.find("\nsobol             3667        no"), std::string::npos) << r.out;
}

TEST(PointsCli, WritesCsvWithIndexXY) {
    const fs::path out = scratch("pts.csv");
    const Result r = run("points --sampler sobol --count 4 --dims 0,1 -o " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    std::ifstream in(out);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), "index,x,y\n0,0,0\n1,0.5,0.5\n2,0.75,0.25\n3,0.25,0.75\n");
}

TEST(PointsCli, PixelSeedAndDimensionsChangeThePoints) {
    const fs::path a = scratch("a.csv"), b = scratch("b.csv");
    ASSERT_EQ(
        run("points --sampler zsobol --count 16 --dims 6,7 --pixel 3,4 --seed 1 -o " + a.string())
            .exitCode,
        0);
    ASSERT_EQ(
        run("points --sampler zsobol --count 16 --dims 6,7 --pixel 3,4 --seed 2 -o " + b.string())
            .exitCode,
        0);
    std::ifstream ia(a), ib(b);
    std::stringstream ta, tb;
    ta << ia.rdbuf(), tb << ib.rdbuf();
    const std::string first = ta.str(), second = tb.str();
    EXPECT_NE(first, second);
    EXPECT_EQ(std::count(first.begin(), first.end(), '\n'), 17);
}

TEST(PointsCli, DrawsSvgAndPngWithSpectrum) {
    const fs::path svg = scratch("pts.svg"), png = scratch("pts.png");
    ASSERT_EQ(run("points --sampler pmj02 --count 256 --dims 2,3 -o " + svg.string()).exitCode, 0);
    ASSERT_EQ(
        run("points --sampler halton-owen --count 256 --dims 0,1 -o " + png.string()).exitCode, 0);
    std::ifstream in(svg);
    std::stringstream text;
    text << in.rdbuf();
    const std::string drawing = text.str();
    EXPECT_NE(drawing.find("<svg"), std::string::npos);
    EXPECT_NE(drawing.find("<polyline"), std::string::npos);
    size_t circles = 0;
    for (size_t at = drawing.find("<circle"); at != std::string::npos;
         at = drawing.find("<circle", at + 1))
        ++circles;
    EXPECT_EQ(circles, 256u);
    std::ifstream pngIn(png, std::ios::binary);
    char magic[8] = {};
    pngIn.read(magic, 8);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST(PointsCli, BadInputExitsTwoWithoutWritingAFile) {
    const fs::path out = scratch("bad.csv");
    for (const std::string args :
         {"--sampler nope --count 4 --dims 0,1", "--sampler sobol --count 0 --dims 0,1",
          "--sampler sobol --count 4 --dims 0", "--sampler sobol --count 4 --dims a,b",
          "--sampler sobol --count 4 --dims 0,1 --pixel 5,5 --resolution 4x4",
          "--sampler sobol --count 4 --dims 0,1 --pixel -1,2"}) {
        const Result r = run("points " + args + " -o " + out.string());
        EXPECT_EQ(r.exitCode, 2) << args << ": " << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
        EXPECT_FALSE(fs::exists(out)) << args;
    }
    const Result r =
        run("points --sampler sobol --count 4 --dims 0,1 -o " + scratch("x.txt").string());
    EXPECT_EQ(r.exitCode, 2);
    const Result missing =
        run("points --sampler sobol --count 4 --dims 0,1 -o /nonexistent/dir/p.csv");
    EXPECT_EQ(missing.exitCode, 2) << missing.out;
}

}  // namespace
