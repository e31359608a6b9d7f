// The HTTP side of `pathlab view` (cpp-httplib): the page's own files and the
// JSON/image API over one ViewSession (docs/view.md lists the endpoints).
// Nothing else is served: no path reaches the file system.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>

#include "view/view_session.h"

namespace httplib {
class Server;
}

namespace pathlab::view {

// Request bodies larger than this are refused (HTTP 413).
constexpr size_t kMaxRequestBody = size_t(1) << 20;

class ViewServer {
  public:
    explicit ViewServer(ViewSession& session);
    ~ViewServer();

    // Binds to host:port (port 0: any free port) and returns the port.
    // Throws InputError when the address is in use or cannot be bound.
    int bind(const std::string& host, int port);
    // Serves until stop() or POST /api/stop; returns whether it was stopped
    // (rather than failing).
    bool listen();
    // From any thread, not from a signal handler. A stop before listen()
    // makes listen() return at once; one while listen() is starting may be
    // lost (call again).
    void stop();

  private:
    void addApiRoutes();
    void addImageRoutes();
    void addPageRoutes();

    // The PNG of the last frame shown, per image (A, B): every open page
    // asks for the same one, which is encoded once. `map`: "image", or the
    // error map "relse" or "flip" (null when there is no reference for it).
    std::shared_ptr<const std::string> displayPng(const Frame& frame, int which,
                                                  const std::string& map);

    std::mutex pngMutex_;
    std::string pngKey_[2];
    std::shared_ptr<const std::string> png_[2];
    ViewSession& session_;
    std::unique_ptr<httplib::Server> http_;
    std::atomic<bool> stopRequested_{false};
};

}  // namespace pathlab::view
