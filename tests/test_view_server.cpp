// `pathlab view`'s HTTP API, on a server started in-process on a free port:
// the endpoints, the float image bit-identical to `pathlab render`, restart
// semantics through POST /api/settings, bad requests, and POST /api/stop.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.h"
#include "core/image.h"
#include "sampling/spectrum.h"
#include "view_test_util.h"

namespace pathlab {
namespace {

using nlohmann::json;
using testing::RunningServer;
using testing::smallViewSettings;

json getJson(httplib::Client& client, const std::string& path, int expectedStatus = 200) {
    const auto res = client.Get(path.c_str());
    EXPECT_TRUE(res) << path;
    if (!res) return {};
    EXPECT_EQ(res->status, expectedStatus) << path << ": " << res->body;
    return json::parse(res->body, nullptr, false);
}

httplib::Result postJson(httplib::Client& client, const std::string& path,
                         const std::string& body) {
    return client.Post(path.c_str(), body, "application/json");
}

TEST(ViewServer, StatusPageAndImages) {
    RunningServer server(smallViewSettings("independent", "sobol"));
    server.session.waitForSpp(1);
    const json status = getJson(server.client, "/api/status");
    for (const char* key : {"scene", "sampler", "compare", "seed", "spp", "width", "height",
                            "paths_per_second", "running"})
        EXPECT_TRUE(status.contains(key)) << key;
    EXPECT_EQ(status["sampler"], "independent");
    EXPECT_EQ(status["compare"], "sobol");
    EXPECT_EQ(status["width"], 32);
    EXPECT_GT(status["paths_per_second"].get<double>(), 0);

    const auto page = server.client.Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    EXPECT_NE(page->body.find("/view.js"), std::string::npos);
    for (const char* asset : {"/view.js", "/view.css", "/index.html"}) {
        const auto res = server.client.Get(asset);
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 200) << asset;
    }
    for (const char* which : {"a", "b"}) {
        const auto png =
            server.client.Get((std::string("/api/image?format=png&which=") + which).c_str());
        ASSERT_TRUE(png);
        EXPECT_EQ(png->status, 200);
        EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
        EXPECT_EQ(png->body.substr(1, 3), "PNG");
    }
    const json options = getJson(server.client, "/api/options");
    EXPECT_FALSE(options["samplers"].empty());
    const json error = getJson(server.client, "/api/error");
    EXPECT_TRUE(error["spp"].is_array());
}

TEST(ViewServer, FloatImageIsTheRenderOfItsSpp) {
    const view::ViewSettings v = smallViewSettings("sobol-owen", "pmj02");
    RunningServer server(v);
    server.session.waitForSpp(4);
    const auto dir = testing::scratchDirectory("view-exr");
    for (const char* which : {"a", "b"}) {
        const auto res =
            server.client.Get((std::string("/api/image?format=exr&which=") + which).c_str());
        ASSERT_TRUE(res);
        ASSERT_EQ(res->status, 200);
        const int spp = std::stoi(res->get_header_value("X-Pathlab-Spp"));
        EXPECT_GE(spp, 4);
        const auto path = dir / (std::string(which) + ".exr");
        std::ofstream(path, std::ios::binary) << res->body;
        const Image served = readImage(path.string());
        const std::string sampler = which[0] == 'a' ? v.sampler : v.compare;
        EXPECT_TRUE(
            testing::sameBytes(served, testing::renderedLike(*server.scene, v, sampler, spp)))
            << sampler << " at " << spp;
    }
    const json pixel = getJson(server.client, "/api/pixel?x=3&y=5");
    EXPECT_EQ(pixel["a"].size(), 3u);
    EXPECT_EQ(pixel["b"].size(), 3u);
    std::filesystem::remove_all(dir);
}

TEST(ViewServer, SettingsRestartOnlyForTheRender) {
    RunningServer server(smallViewSettings("independent"));
    const uint64_t generation = server.session.waitForSpp(1).generation;
    auto res =
        postJson(server.client, "/api/settings", R"({"exposure": -1, "tone_map": "linear"})");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    json status = json::parse(res->body);
    EXPECT_EQ(status["generation"], generation);
    EXPECT_EQ(status["tone_map"], "linear");
    res = postJson(server.client, "/api/settings", R"({"sampler": "halton", "max_depth": 2})");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    status = json::parse(res->body);
    EXPECT_EQ(status["generation"], generation + 1);
    EXPECT_EQ(status["sampler"], "halton");
    EXPECT_EQ(status["max_depth"], 2);
    EXPECT_EQ(status["equal"], "spp");
    res = postJson(server.client, "/api/settings", R"({"equal": "time"})");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    status = json::parse(res->body);
    EXPECT_EQ(status["equal"], "time");
    EXPECT_EQ(status["generation"], generation + 2) << "the A/B mode restarts";
    EXPECT_TRUE(status["spp_b"].is_null()) << "no compare sampler, no B count";
    res = postJson(server.client, "/api/reset", "{}");
    ASSERT_TRUE(res);
    EXPECT_EQ(json::parse(res->body)["generation"], generation + 3);
}

TEST(ViewServer, DisplayChangesReachThePng) {
    RunningServer server(smallViewSettings("independent"));
    server.session.waitForSpp(1);
    ASSERT_TRUE(postJson(server.client, "/api/settings", R"({"paused": true})"));
    server.session.waitUntilIdle();
    const auto png = [&] { return server.client.Get("/api/image?which=a&format=png")->body; };
    const std::string first = png();
    EXPECT_EQ(png(), first) << "the same frame and display give the same PNG";
    ASSERT_TRUE(postJson(server.client, "/api/settings", R"({"exposure": 2})"));
    const std::string brighter = png();
    EXPECT_NE(brighter, first);
    ASSERT_TRUE(postJson(server.client, "/api/settings", R"({"tone_map": "aces"})"));
    EXPECT_NE(png(), brighter);
}

TEST(ViewServer, BadRequestsAreRefusedAndChangeNothing) {
    RunningServer server(smallViewSettings("independent"));
    server.session.waitForSpp(1);
    const uint64_t generation = server.session.status().generation;
    const auto refused = [&](const std::string& body, const std::string& named) {
        const auto res = postJson(server.client, "/api/settings", body);
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 400) << body;
        const json error = json::parse(res->body, nullptr, false);
        ASSERT_TRUE(error.contains("error")) << res->body;
        EXPECT_NE(error["error"].get<std::string>().find(named), std::string::npos) << res->body;
    };
    refused(R"({"sampler": "no-such-sampler"})", "no-such-sampler");
    refused(R"({"max_depth": 5000})", "max_depth");
    refused(R"({"scene": "/no/such/scene.json"})", "scene.json");
    refused(R"({"sampler": )", "JSON");
    refused(R"({"equal": "fast"})", "equal");
    refused(R"({"equal": 1})", "equal");
    EXPECT_EQ(server.session.status().generation, generation);
    EXPECT_EQ(server.session.status().settings.sampler, "independent");

    for (const char* path : {"/etc/passwd", "/../CMakeLists.txt", "/api/nothing", "/web/view.js",
                             "/src/view/web/index.html"}) {
        const auto res = server.client.Get(path);
        ASSERT_TRUE(res) << path;
        EXPECT_EQ(res->status, 404) << path;
    }
    const auto huge = postJson(server.client, "/api/settings",
                               "{\"scene\": \"" + std::string(view::kMaxRequestBody, 'x') + "\"}");
    ASSERT_TRUE(huge);
    EXPECT_EQ(huge->status, 413);
    getJson(server.client, "/api/image?which=c", 400);
    getJson(server.client, "/api/image?which=b", 404);  // no compare sampler
    getJson(server.client, "/api/pixel?x=32&y=0", 400);
    getJson(server.client, "/api/pixel?x=1e3&y=0", 400);
    getJson(server.client, "/api/image?map=flip", 404);  // no reference
    getJson(server.client, "/api/image?map=mse", 400);
    getJson(server.client, "/api/image?map=relse&format=exr", 400);
}

// The CSV rows "index,x,y" of `pathlab points`.
std::vector<std::pair<float, float>> csvPoints(const std::string& csv) {
    std::vector<std::pair<float, float>> points;
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
        const size_t a = line.find(','), b = line.find(',', a + 1);
        points.emplace_back(std::stof(line.substr(a + 1, b - a - 1)),
                            std::stof(line.substr(b + 1)));
    }
    return points;
}

TEST(ViewServer, PointsAreThoseOfPathlabPointsWithTheirSpectrum) {
    const view::ViewSettings v = smallViewSettings("sobol-owen", "pmj02");
    RunningServer server(v);
    server.session.waitForSpp(1);
    const auto dir = testing::scratchDirectory("view-points");
    for (const char* which : {"a", "b"}) {
        const json p = getJson(server.client, std::string("/api/points?pixel=5,7&dims=2,3&count=64"
                                                          "&which=") +
                                                  which);
        const std::string sampler = which[0] == 'a' ? v.sampler : v.compare;
        EXPECT_EQ(p["sampler"], sampler);
        const auto csv = dir / "points.csv";
        const auto cli = testing::runPathlab("points --sampler " + sampler +
                                                 " --count 64 --dims 2,3 --pixel 5,7 "
                                                 "--resolution 32x24 --seed 11 -o " +
                                                 csv.string(),
                                             dir);
        ASSERT_EQ(cli.exitCode, 0) << cli.err;
        const auto expected = csvPoints(testing::slurpFile(csv));
        ASSERT_EQ(p["points"].size(), expected.size());
        for (size_t k = 0; k < expected.size(); ++k) {
            EXPECT_EQ(p["points"][k][0].get<float>(), expected[k].first) << sampler << " " << k;
            EXPECT_EQ(p["points"][k][1].get<float>(), expected[k].second) << sampler << " " << k;
        }
        // The periodogram's zero frequency is the point count; the rings are
        // those of `pathlab points`' spectrum of the same points.
        std::vector<Vec2f> points;
        for (const auto& [x, y] : expected) points.push_back({x, y});
        const int f = p["spectrum"]["max_frequency"];
        const auto radial = p["spectrum"]["radial"].get<std::vector<double>>();
        EXPECT_EQ(radial, radialPowerSpectrum(points, f));
        EXPECT_NEAR(radial[0], 64.0, 1e-9);
        const json& image = p["spectrum_image"];
        const int side = image["size"];
        EXPECT_EQ(side, 2 * image["max_frequency"].get<int>() + 1);
        ASSERT_EQ(image["log10_power"].size(), size_t(side) * side);
        EXPECT_NEAR(image["log10_power"][side * side / 2].get<double>(), std::log10(64.0), 0.01);
    }
    std::filesystem::remove_all(dir);
}

TEST(ViewServer, ErrorMapsAreDrawnAgainstTheReference) {
    view::ViewSettings v = smallViewSettings("independent");
    v.maxSpp = 4;
    const auto scene = view::loadViewScene(v.scene);
    RunningServer server(
        v, std::make_shared<const Image>(testing::renderedLike(*scene, v, "sobol-owen", 64)));
    server.session.waitForSpp(4);
    const auto dir = testing::scratchDirectory("view-maps");
    std::map<std::string, std::string> pngs;
    for (const char* map : {"image", "relse", "flip"}) {
        const auto res = server.client.Get((std::string("/api/image?map=") + map).c_str());
        ASSERT_TRUE(res);
        ASSERT_EQ(res->status, 200) << map << ": " << res->body;
        pngs[map] = res->body;
        const auto path = dir / (std::string(map) + ".png");
        std::ofstream(path, std::ios::binary) << res->body;
        const Image decoded = readImage(path.string());
        EXPECT_EQ(decoded.width, 32);
        EXPECT_EQ(decoded.height, 24);
    }
    EXPECT_NE(pngs["image"], pngs["relse"]);
    EXPECT_NE(pngs["image"], pngs["flip"]);
    EXPECT_NE(pngs["relse"], pngs["flip"]);
    std::filesystem::remove_all(dir);
}

TEST(ViewServer, BadPointsRequestsNameTheParameter) {
    RunningServer server(smallViewSettings("independent"));
    server.session.waitForSpp(1);
    const auto refused = [&](const std::string& query, const std::string& named) {
        const json error = getJson(server.client, "/api/points?" + query, 400);
        ASSERT_TRUE(error.contains("error")) << query;
        EXPECT_EQ(error["error"].get<std::string>().rfind(named, 0), 0u)
            << query << ": " << error["error"];
    };
    refused("dims=0,1", "pixel is missing");
    refused("pixel=32,0", "pixel 32,0 is outside the 32x24 image");
    refused("pixel=3,24", "pixel 3,24 is outside");
    refused("pixel=-1,2", "pixel must look like X,Y");
    refused("pixel=1;2", "pixel must look like X,Y");
    refused("pixel=1,2&dims=3,3", "dims must name two different dimensions");
    refused("pixel=1,2&dims=3", "dims must look like I,J");
    refused("pixel=1,2&dims=1,99999999", "dims must look like I,J");
    refused("pixel=1,2&count=0", "count must be an integer between 1 and 4096");
    refused("pixel=1,2&count=5000", "count must be");
    refused("pixel=1,2&which=b", "which is b but there is no compare sampler");
    refused("pixel=1,2&which=c", "which must be a or b");
    const json ok = getJson(server.client, "/api/points?pixel=31,23");
    EXPECT_EQ(ok["dims"], json::array({0, 1}));
    EXPECT_GE(ok["count"].get<int>(), 1);
}

TEST(ViewServer, StopEndsServing) {
    RunningServer server(smallViewSettings("independent"));
    const auto res = postJson(server.client, "/api/stop", "");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
    server.waitUntilStopped();
    EXPECT_TRUE(server.stoppedCleanly);
}

}  // namespace
}  // namespace pathlab
