// A `pathlab view` server started in-process on a free port of 127.0.0.1,
// with an HTTP client for it.
#pragma once

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <memory>
#include <thread>

#include "image_test_util.h"
#include "render/renderer.h"
#include "view/view_server.h"
#include "view/view_session.h"

namespace pathlab::testing {

// Small, quick settings: a 32×24 Cornell box of depth 4.
inline view::ViewSettings smallViewSettings(const std::string& sampler,
                                            const std::string& compare = "") {
    view::ViewSettings s;
    s.sampler = sampler;
    s.compare = compare;
    s.seed = 11;
    s.size = {32, 24};
    s.maxDepth = 4;
    s.maxSpp = 4096;
    return s;
}

// What `pathlab render` makes of the same settings at `spp`.
inline Image renderedLike(const RenderScene& scene, const view::ViewSettings& v,
                          const std::string& sampler, int spp) {
    RenderSettings s;
    s.sampler = sampler;
    s.samplesPerPixel = spp;
    s.seed = v.seed;
    s.resolution = v.size;
    s.maxDepth = v.maxDepth;
    s.russianRoulette = v.russianRoulette;
    return render(scene, s).image;
}

class RunningServer {
  public:
    explicit RunningServer(const view::ViewSettings& settings,
                           std::shared_ptr<const Image> reference = nullptr)
        : scene(view::loadViewScene(settings.scene)),
          session(settings, scene, 2, std::move(reference)),
          server(session),
          port(server.bind("127.0.0.1", 0)),
          client("127.0.0.1", port) {
        listener_ = std::thread([this] {
            stoppedCleanly = server.listen();
            finished_ = true;
        });
    }
    ~RunningServer() {
        // A stop before the listener has started listening would be lost.
        while (!finished_) {
            server.stop();
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        listener_.join();
    }
    // Waits for the listener to return by itself (POST /api/stop).
    void waitUntilStopped() {
        while (!finished_) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }

    std::shared_ptr<const RenderScene> scene;
    view::ViewSession session;
    view::ViewServer server;
    int port;
    httplib::Client client;
    bool stoppedCleanly = false;

  private:
    std::atomic<bool> finished_{false};
    std::thread listener_;
};

}  // namespace pathlab::testing
