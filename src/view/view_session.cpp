#include "view/view_session.h"

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "render/accumulation.h"
#include "scene/embree_accel.h"
#include "scene/loader.h"

namespace pathlab::view {
namespace {

using Clock = std::chrono::steady_clock;

RenderSettings renderSettingsFor(const ViewSettings& v, const std::string& sampler, int threads,
                                 RenderControl* control) {
    RenderSettings s;
    s.sampler = sampler;
    s.seed = v.seed;
    s.resolution = v.size;
    s.maxDepth = v.maxDepth;
    s.russianRoulette = v.russianRoulette;
    s.threads = threads;
    s.control = control;
    return s;
}

// The sample count of the next pass. The first pass is 1 spp, so a restart
// shows an image at once. Progressive samplers then add a batch that doubles
// up to kPacketWidth samples, and beyond while passes take under 0.25 s, and
// halves when one takes over 1 s, but never below kPacketWidth: a pixel's samples are
// traced as packets of eight and their paths in batches
// (render/path_integrator.h), and passes of one sample would leave the
// packets nearly empty — at 512² sixteen 1-spp passes took 1.9 times as long
// as one 16-spp render (bench/view_interactivity.py). Other samplers render
// each pass afresh: doubling the count keeps the total within twice the last
// pass.
int nextSampleCount(int spp, bool progressive, double lastPassSeconds, int& batch, int maxSpp) {
    if (spp == 0) return 1;
    if (!progressive) return std::min(maxSpp, spp * 2);
    if ((batch < kPacketWidth || lastPassSeconds < 0.25) && batch < (1 << 20)) batch *= 2;
    if (lastPassSeconds > 1.0 && batch > kPacketWidth) batch /= 2;
    return int(std::min<int64_t>(maxSpp, int64_t(spp) + batch));
}

}  // namespace

std::shared_ptr<const RenderScene> loadViewScene(const std::string& scene) {
    return std::make_shared<const RenderScene>(loadScene(scene));
}

ViewSession::ViewSession(ViewSettings settings, std::shared_ptr<const RenderScene> scene,
                         int threads, std::shared_ptr<const Image> reference)
    : settings_(std::move(settings)), scene_(std::move(scene)), threads_(threads) {
    validateViewSettings(settings_);
    if (reference) {
        errors_ = std::make_unique<ErrorHistory>(std::move(reference));
        referenceScene_ = settings_.scene;
    }
    requestRestartLocked();  // generation 1; no other thread yet
    worker_ = std::thread([this] { work(); });
}

ViewSession::~ViewSession() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
        control_.cancel = true;
    }
    changed_.notify_all();
    worker_.join();
}

void ViewSession::work() {
    std::unique_ptr<Accumulation> a, b;
    std::shared_ptr<const RenderScene> scene;
    uint64_t generation = 0;
    int batch = 1;
    double lastPass = 0;
    for (;;) {
        int target = 0;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            const auto hasWork = [&] {
                return stopping_ || restart_ ||
                       (!settings_.paused && error_.empty() && frame_.spp < settings_.maxSpp);
            };
            if (!hasWork()) {
                idle_ = true;
                changed_.notify_all();
                changed_.wait(lock, hasWork);
                idle_ = false;
            }
            if (stopping_) return;
            if (restart_) {
                restart_ = false;
                control_.cancel = false;
                error_.clear();
                scene = scene_;
                a = std::make_unique<Accumulation>(
                    renderSettingsFor(settings_, settings_.sampler, threads_, &control_));
                b = settings_.compare.empty()
                        ? nullptr
                        : std::make_unique<Accumulation>(
                              renderSettingsFor(settings_, settings_.compare, threads_, &control_));
                generation = frame_.generation;
                batch = 1, lastPass = 0;
                if (errors_) errors_->clear();
                changed_.notify_all();
            }
            const bool progressive = a->progressive() && (!b || b->progressive());
            target = nextSampleCount(frame_.spp, progressive, lastPass, batch, settings_.maxSpp);
        }
        const Clock::time_point start = Clock::now();
        try {
            a->advance(*scene, target);
            if (b) b->advance(*scene, target);
        } catch (const RenderCancelled&) {
            continue;  // whoever cancelled asked for a restart or a stop
        } catch (const std::exception& e) {
            std::lock_guard<std::mutex> lock(mutex_);
            error_ = e.what();
            changed_.notify_all();
            continue;
        }
        lastPass = std::chrono::duration<double>(Clock::now() - start).count();
        bool measure = false;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (generation != frame_.generation || restart_) continue;
            frame_.a = std::make_shared<const Image>(a->image());
            frame_.b = b ? std::make_shared<const Image>(b->image()) : nullptr;
            frame_.spp = target;
            renderSeconds_ = a->seconds() + (b ? b->seconds() : 0);
            paths_ = a->paths() + (b ? b->paths() : 0);
            measure = errors_ && errors_->due(target) && referenceFits(a->image());
            changed_.notify_all();
        }
        if (!measure) continue;
        // Outside the lock: ꟻLIP takes a while, and only this thread uses errors_.
        errors_->measure(target, a->image(), b ? &b->image() : nullptr);
        std::lock_guard<std::mutex> lock(mutex_);
        if (generation == frame_.generation) errorPoints_ = errors_->points();
    }
}

// Called with the lock held.
bool ViewSession::referenceFits(const Image& image) const {
    return errors_ && settings_.scene == referenceScene_ &&
           errors_->reference().width == image.width && errors_->reference().height == image.height;
}

std::vector<float> ViewSession::errorMap(const Image& image, ErrorMapKind kind) const {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!referenceFits(image)) return {};
    }
    return errors_->errorMap(image, kind);  // errors_ never changes after construction
}

std::vector<ErrorPoint> ViewSession::errorPoints() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return errorPoints_;
}

SessionStatus ViewSession::update(const nlohmann::json& changes) {
    std::unique_lock<std::mutex> lock(mutex_);
    ViewSettings next = applySettingsJson(settings_, changes);
    std::shared_ptr<const RenderScene> scene = scene_;
    if (next.scene != settings_.scene) {
        lock.unlock();  // loading may take a while; the render goes on meanwhile
        scene = loadViewScene(next.scene);
        lock.lock();
        // Another request may have changed the settings meanwhile: apply the
        // changes to those, with the scene just loaded.
        next = applySettingsJson(settings_, changes);
    }
    const bool restart = !next.sameRender(settings_) || scene != scene_;
    settings_ = std::move(next);
    scene_ = std::move(scene);
    if (restart) requestRestartLocked();
    changed_.notify_all();
    lock.unlock();
    return status();
}

void ViewSession::reset() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        requestRestartLocked();
    }
    changed_.notify_all();
}

// The new generation starts now, with no image: status and frames say so at
// once, while the worker finishes cancelling the pass under way.
void ViewSession::requestRestartLocked() {
    restart_ = true;
    control_.cancel = true;
    frame_ = Frame{nullptr, nullptr, 0, frame_.generation + 1};
    errorPoints_.clear();
    renderSeconds_ = 0, paths_ = 0, started_ = Clock::now();
}

Frame ViewSession::frame() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return frame_;
}

SessionStatus ViewSession::status() const {
    std::lock_guard<std::mutex> lock(mutex_);
    SessionStatus s;
    s.settings = settings_;
    s.spp = frame_.spp;
    if (frame_.a) s.width = frame_.a->width, s.height = frame_.a->height;
    s.pathsPerSecond = renderSeconds_ > 0 ? double(paths_) / renderSeconds_ : 0;
    s.elapsed = std::chrono::duration<double>(Clock::now() - started_).count();
    s.running = !settings_.paused && error_.empty() && frame_.spp < settings_.maxSpp;
    s.generation = frame_.generation;
    s.error = error_;
    s.reference = frame_.a && referenceFits(*frame_.a);
    return s;
}

void ViewSession::waitUntilIdle() const {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return idle_ || stopping_; });
}

Frame ViewSession::waitForSpp(int spp) const {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock,
                  [&] { return stopping_ || !error_.empty() || (!restart_ && frame_.spp >= spp); });
    return frame_;
}

}  // namespace pathlab::view
