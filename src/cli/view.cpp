// `pathlab view`: the browser lab — a progressive render served over HTTP
// (src/view, docs/view.md) until Ctrl-C or POST /api/stop.
#include <pthread.h>
#include <signal.h>

#include <cstdio>
#include <memory>
#include <thread>

#include "cli/commands.h"
#include "core/error.h"
#include "core/image.h"
#include "core/seed.h"
#include "render/render_options.h"
#include "view/view_server.h"
#include "view/view_session.h"

namespace pathlab::cli {
namespace {

struct ViewOptions {
    view::ViewSettings settings;
    std::string size, seed = "0", host = "127.0.0.1", reference, equal = "spp";
    int port = 8642, threads = 0;
    bool noRoulette = false;
};

// Ctrl-C and SIGTERM are taken by a thread of their own (sigwait), which
// stops the server from outside any signal handler; every other thread,
// started after this, has them blocked.
class SignalStopper {
  public:
    SignalStopper() {
        sigemptyset(&signals_);
        for (int s : {SIGINT, SIGTERM, SIGUSR1}) sigaddset(&signals_, s);
        pthread_sigmask(SIG_BLOCK, &signals_, &previous_);
    }
    void watch(view::ViewServer& server) {
        thread_ = std::thread([this, &server] {
            int signal = 0;
            sigwait(&signals_, &signal);
            if (signal != SIGUSR1) server.stop();  // SIGUSR1: the server stopped by itself
        });
    }
    // Ends the watching thread; call before the server it stops is gone.
    void release() {
        if (!thread_.joinable()) return;
        pthread_kill(thread_.native_handle(), SIGUSR1);
        thread_.join();
    }
    ~SignalStopper() {
        release();
        pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
    }

  private:
    sigset_t signals_, previous_;
    std::thread thread_;
};

void runView(ViewOptions& o) {
    view::ViewSettings& s = o.settings;
    s.seed = parseSeed(o.seed);
    s.russianRoulette = !o.noRoulette;
    s.equal = view::parseEqualBy(o.equal, "--equal");
    if (!o.size.empty()) s.size = parseImageSize(o.size, "--size");
    if (s.maxDepth < 0 || s.maxDepth > 1024)
        throw InputError("--max-depth must be between 0 and 1024, got " +
                         std::to_string(s.maxDepth));
    if (s.maxSpp < 1 || s.maxSpp > (1 << 24))
        throw InputError("--max-spp must be between 1 and 16777216, got " +
                         std::to_string(s.maxSpp));
    if (o.threads < 0) throw InputError("--threads must be 0 (all cores) or more");
    if (o.port < 0 || o.port > 65535)
        throw InputError("--port must be between 0 and 65535, got " + std::to_string(o.port));
    view::validateViewSettings(s);
    SignalStopper signals;  // before any thread starts
    std::shared_ptr<const Image> reference;
    if (!o.reference.empty()) {
        reference = std::make_shared<const Image>(readImage(o.reference));
        if (s.size.x > 0 && (reference->width != s.size.x || reference->height != s.size.y))
            throw InputError("--reference '" + o.reference + "' is " +
                             std::to_string(reference->width) + "x" +
                             std::to_string(reference->height) + ", not the --size " + o.size);
    }
    view::ViewSession session(s, view::loadViewScene(s.scene, s.lightSampler), o.threads,
                              reference);
    view::ViewServer server(session);
    const int port = server.bind(o.host, o.port);
    std::printf(
        "pathlab view: http://%s:%d/ (Ctrl-C stops)\n",
        o.host.find(':') != std::string::npos ? ("[" + o.host + "]").c_str() : o.host.c_str(),
        port);
    std::fflush(stdout);
    signals.watch(server);
    const bool stopped = server.listen();
    signals.release();
    if (!stopped) throw std::runtime_error("the HTTP server failed");
}

}  // namespace

void addViewCommand(CLI::App& app) {
    auto o = std::make_shared<ViewOptions>();
    CLI::App* cmd = app.add_subcommand("view", "Render progressively and watch it in a browser");
    cmd->add_option("--scene", o->settings.scene,
                    "cornell-box, wolf, or a scene file (.json/.obj/.pbrt)")
        ->required();
    cmd->add_option("--sampler", o->settings.sampler, "Sampler name (see `pathlab samplers`)")
        ->capture_default_str();
    cmd->add_option("--compare", o->settings.compare, "A second sampler, rendered beside A");
    cmd->add_option("--equal", o->equal,
                    "Compare A and B at equal spp or at equal render time (spp|time)")
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the samplers' randomisation")
        ->capture_default_str();
    cmd->add_option("--size", o->size, "Image size WIDTHxHEIGHT (default: the scene's)");
    cmd->add_option("--max-depth", o->settings.maxDepth, "Maximum path depth")
        ->capture_default_str();
    cmd->add_flag("--no-russian-roulette", o->noRoulette, "Disable Russian roulette");
    cmd->add_option("--light-sampler", o->settings.lightSampler,
                    "How next-event estimation picks a light: uniform, power or bvh "
                    "(default: the scene file's choice, else power)");
    cmd->add_flag("--spectral", o->settings.spectral,
                  "Carry four sampled wavelengths per path instead of RGB");
    cmd->add_option("--max-spp", o->settings.maxSpp, "Stop accumulating at this spp")
        ->capture_default_str();
    cmd->add_option("--reference", o->reference,
                    "A converged image (.exr/.pfm) to measure MSE and FLIP against, live");
    cmd->add_option("--host", o->host, "Address to listen on (0.0.0.0: every interface)")
        ->capture_default_str();
    cmd->add_option("--port", o->port, "Port to listen on (0: any free port)")
        ->capture_default_str();
    cmd->add_option("--threads", o->threads, "Render threads (0 = all cores)")
        ->capture_default_str();
    cmd->callback([o] { runView(*o); });
}

}  // namespace pathlab::cli
