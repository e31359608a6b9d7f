// `pathlab view`'s HTTP API, on a server started in-process on a free port:
// the endpoints, the float image bit-identical to `pathlab render`, restart
// semantics through POST /api/settings, bad requests, and POST /api/stop.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "core/image.h"
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
    res = postJson(server.client, "/api/reset", "{}");
    ASSERT_TRUE(res);
    EXPECT_EQ(json::parse(res->body)["generation"], generation + 2);
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
