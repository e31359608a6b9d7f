#include "view/view_server.h"

#include <httplib.h>
#include <sys/socket.h>

#include <algorithm>
#include <charconv>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/error.h"
#include "metrics/error_map.h"
#include "sampling/registry.h"
#include "scene/loader.h"
#include "view/error_history.h"
#include "view/points_json.h"
#include "view/status_json.h"
#include "view/tone_map.h"
#include "view/web_assets.h"

namespace pathlab::view {
namespace {

using nlohmann::json;

void sendJson(httplib::Response& res, const json& body, int status = 200) {
    res.status = status;
    res.set_header("Cache-Control", "no-store");
    res.set_content(body.dump(), "application/json");
}

// 204: what was asked for exists once the next pass lands (just after a start
// or restart). Not an error: a page polling at that moment logs nothing.
void sendNothingYet(httplib::Response& res) {
    res.status = 204;
    res.set_header("Cache-Control", "no-store");
}

void sendError(httplib::Response& res, int status, const std::string& message) {
    sendJson(res, json{{"error", message}}, status);
}

// The request's query parameter, or `fallback` when it has none.
std::string param(const httplib::Request& req, const char* name, const char* fallback) {
    return req.has_param(name) ? req.get_param_value(name) : fallback;
}

const char* mimeType(const std::string& path) {
    const auto endsWith = [&](const char* ext) {
        const std::string e(ext);
        return path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0;
    };
    if (endsWith(".html")) return "text/html; charset=utf-8";
    if (endsWith(".js")) return "text/javascript; charset=utf-8";
    if (endsWith(".css")) return "text/css; charset=utf-8";
    if (endsWith(".svg")) return "image/svg+xml";
    return "application/octet-stream";
}

// Strict integer parsing of a query parameter; nullopt for anything else.
std::optional<int> intParam(const httplib::Request& req, const char* name) {
    if (!req.has_param(name)) return std::nullopt;
    const std::string text = req.get_param_value(name);
    int v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return v;
}

json pixelJson(const std::shared_ptr<const Image>& image, int x, int y) {
    if (!image) return nullptr;
    const Vec3f c = image->at(x, y);
    return json::array({c.x, c.y, c.z});
}

}  // namespace

ViewServer::ViewServer(ViewSession& session)
    : session_(session), http_(std::make_unique<httplib::Server>()) {
    http_->set_payload_max_length(kMaxRequestBody);
    // SO_REUSEADDR only: httplib's default SO_REUSEPORT would let a second
    // server share a port already in use instead of failing.
    http_->set_socket_options([](socket_t sock) {
        int yes = 1;
        setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });
    http_->set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, std::exception_ptr e) {
            try {
                std::rethrow_exception(e);
            } catch (const std::exception& x) {
                sendError(res, 500, x.what());
            } catch (...) {
                sendError(res, 500, "unknown error");
            }
        });
    addApiRoutes();
    addImageRoutes();
    addPageRoutes();
}

ViewServer::~ViewServer() = default;

int ViewServer::bind(const std::string& host, int port) {
    const std::string where = host + ":" + std::to_string(port);
    if (port < 0 || port > 65535)
        throw InputError("--port must be between 0 and 65535, got " + std::to_string(port));
    if (port == 0) {
        const int bound = http_->bind_to_any_port(host);
        if (bound < 0) throw InputError("cannot listen on " + host + " (no free port?)");
        return bound;
    }
    if (!http_->bind_to_port(host, port))
        throw InputError("cannot listen on " + where + " (address in use or not available)");
    return port;
}

bool ViewServer::listen() {
    return stopRequested_ || http_->listen_after_bind();
}

void ViewServer::stop() {
    stopRequested_ = true;
    http_->stop();
}

void ViewServer::addApiRoutes() {
    http_->Get("/api/status", [this](const httplib::Request&, httplib::Response& res) {
        sendJson(res, statusJson(session_.status()));
    });
    http_->Post("/api/settings", [this](const httplib::Request& req, httplib::Response& res) {
        json changes;
        try {
            changes = json::parse(req.body);
        } catch (const json::parse_error&) {
            return sendError(res, 400, "the request body is not JSON");
        }
        try {
            sendJson(res, statusJson(session_.update(changes)));
        } catch (const InputError& e) {
            sendError(res, 400, e.what());
        }
    });
    http_->Post("/api/reference", [this](const httplib::Request& req, httplib::Response& res) {
        const json body = json::parse(req.body, nullptr, false);
        if (body.is_discarded()) return sendError(res, 400, "the request body is not JSON");
        if (!body.is_object() || !body.contains("spp") || !body["spp"].is_number_integer())
            return sendError(res, 400, "reference spp must be an integer: {\"spp\": N}");
        const int64_t spp = body["spp"].get<int64_t>();
        try {
            session_.buildReference(int(std::clamp<int64_t>(spp, 0, INT32_MAX)));
        } catch (const InputError& e) {
            return sendError(res, 400, e.what());
        }
        sendJson(res, statusJson(session_.status()));
    });
    http_->Post("/api/reset", [this](const httplib::Request&, httplib::Response& res) {
        session_.reset();
        sendJson(res, statusJson(session_.status()));
    });
    http_->Post("/api/stop", [this](const httplib::Request&, httplib::Response& res) {
        sendJson(res, json{{"stopping", true}});
        http_->stop();  // listen() returns once this response is sent
    });
    http_->Get("/api/options", [](const httplib::Request&, httplib::Response& res) {
        json samplers = json::array();
        for (const SamplerInfo& info : samplerInfos())
            samplers.push_back({{"name", info.name},
                                {"description", info.description},
                                {"progressive", info.progressive}});
        sendJson(res, json{{"samplers", samplers}, {"scenes", builtinSceneNames()}});
    });
    http_->Get("/api/points", [this](const httplib::Request& req, httplib::Response& res) {
        const SessionStatus status = session_.status();
        if (status.width == 0) return sendNothingYet(res);
        const PointsQuery query{param(req, "pixel", ""), param(req, "dims", "0,1"),
                                param(req, "count", ""), param(req, "which", "a")};
        try {
            sendJson(res, pointsJson(status, query));
        } catch (const InputError& e) {
            sendError(res, 400, e.what());
        }
    });
    http_->Get("/api/error", [this](const httplib::Request&, httplib::Response& res) {
        const bool hasB = !session_.status().settings.compare.empty();
        sendJson(res, errorJson(session_.errorPoints(), hasB));
    });
}

void ViewServer::addImageRoutes() {
    http_->Get("/api/image", [this](const httplib::Request& req, httplib::Response& res) {
        const std::string which = param(req, "which", "a"), format = param(req, "format", "png");
        const std::string map = param(req, "map", "image");
        if (which != "a" && which != "b") return sendError(res, 400, "which must be a or b");
        if (format != "png" && format != "exr" && format != "pfm")
            return sendError(res, 400, "format must be png, exr or pfm");
        if (map != "image" && map != "relse" && map != "flip")
            return sendError(res, 400, "map must be image, relse or flip");
        if (map != "image" && format != "png")
            return sendError(res, 400, "map " + map + " is drawn as png only");
        const Frame frame = session_.frame();
        const std::shared_ptr<const Image>& image = which == "a" ? frame.a : frame.b;
        if (!image) {
            if (which == "b" && session_.status().settings.compare.empty())
                return sendError(res, 404, "no compare sampler");
            return sendNothingYet(res);  // before the first pass (at equal time: B's)
        }
        res.set_header("Cache-Control", "no-store");
        res.set_header("X-Pathlab-Spp", std::to_string(which == "a" ? frame.spp : frame.sppB));
        res.set_header("X-Pathlab-Generation", std::to_string(frame.generation));
        if (format == "png") {
            const std::shared_ptr<const std::string> png =
                displayPng(frame, which == "a" ? 0 : 1, map);
            if (!png) return sendError(res, 404, "no reference for this image");
            res.set_content(png->data(), png->size(), "image/png");
        } else if (format == "exr") {
            res.set_content(encodeImage(*image, ImageFormat::Exr), "image/x-exr");
        } else {
            res.set_content(encodeImage(*image, ImageFormat::Pfm), "image/x-portable-floatmap");
        }
    });
    http_->Get("/api/pixel", [this](const httplib::Request& req, httplib::Response& res) {
        const std::optional<int> x = intParam(req, "x"), y = intParam(req, "y");
        const Frame frame = session_.frame();
        if (!x || !y) return sendError(res, 400, "x and y must be integers");
        if (!frame.a) return sendNothingYet(res);
        if (*x < 0 || *y < 0 || *x >= frame.a->width || *y >= frame.a->height)
            return sendError(res, 400, "pixel outside the image");
        sendJson(res, json{{"x", *x},
                           {"y", *y},
                           {"spp", frame.spp},
                           {"spp_b", frame.b ? json(frame.sppB) : json()},
                           {"a", pixelJson(frame.a, *x, *y)},
                           {"b", pixelJson(frame.b, *x, *y)}});
    });
}

std::shared_ptr<const std::string> ViewServer::displayPng(const Frame& frame, int which,
                                                          const std::string& map) {
    const ViewSettings s = session_.status().settings;
    const int spp = which == 0 ? frame.spp : frame.sppB;
    const std::string key = std::to_string(frame.generation) + "/" + std::to_string(spp) + "/" +
                            std::to_string(s.exposure) + "/" + toneMapName(s.toneMap) + "/" + map;
    {
        std::lock_guard<std::mutex> lock(pngMutex_);
        if (pngKey_[which] == key) return png_[which];
    }
    const Image& image = which == 0 ? *frame.a : *frame.b;
    std::shared_ptr<const std::string> png;
    if (map == "image") {
        png = std::make_shared<const std::string>(encodeDisplayPng(image, s.exposure, s.toneMap));
    } else {
        // Error maps in magma (metrics/error_map.h), as `pathlab compare --error-map`.
        const std::vector<float> errors = session_.errorMap(
            image, map == "flip" ? ErrorMapKind::Flip : ErrorMapKind::RelativeSquared);
        if (errors.empty()) return nullptr;
        png = std::make_shared<const std::string>(encodeImage(
            errorMapImage(errors, image.width, image.height, ImageFormat::Png), ImageFormat::Png));
    }
    std::lock_guard<std::mutex> lock(pngMutex_);
    pngKey_[which] = key, png_[which] = png;
    return png;
}

void ViewServer::addPageRoutes() {
    for (const WebAsset& asset : webAssets()) {
        const std::string path = asset.path;
        const auto serve = [asset, path](const httplib::Request&, httplib::Response& res) {
            res.set_content(reinterpret_cast<const char*>(asset.data), asset.size, mimeType(path));
        };
        http_->Get(path, serve);
        if (path == "/index.html") http_->Get("/", serve);
    }
}

}  // namespace pathlab::view
