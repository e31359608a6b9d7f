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
    std::unique_ptr<Accumulation> acc[2];  // A, B (null without a compare sampler)
    std::unique_ptr<PassScheduler> plan;
    std::shared_ptr<const RenderScene> scene;
    uint64_t generation = 0;
    for (;;) {
        Pass pass;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            const auto hasWork = [&] {
                return stopping_ || restart_ ||
                       (!settings_.paused && error_.empty() && !plan->done());
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
                startLocked(acc, plan);
                generation = frame_.generation;
                changed_.notify_all();
            }
            pass = plan->next();
        }
        double seconds[2] = {0, 0};
        try {
            for (int i : {0, 1}) {
                if (pass.target[i] == 0) continue;
                const double before = acc[i]->seconds();
                acc[i]->advance(*scene, pass.target[i]);
                seconds[i] = acc[i]->seconds() - before;
            }
        } catch (const RenderCancelled&) {
            continue;  // whoever cancelled asked for a restart or a stop
        } catch (const std::exception& e) {
            std::lock_guard<std::mutex> lock(mutex_);
            error_ = e.what();
            changed_.notify_all();
            continue;
        }
        plan->finished(pass, seconds[0], seconds[1]);
        if (publish(generation, pass, acc)) measureError(generation, acc);
    }
}

// A new generation: fresh accumulations and pass schedule for the settings.
void ViewSession::startLocked(std::unique_ptr<Accumulation> (&acc)[2],
                              std::unique_ptr<PassScheduler>& plan) {
    const ViewSettings& s = settings_;
    acc[0] = std::make_unique<Accumulation>(renderSettingsFor(s, s.sampler, threads_, &control_));
    acc[1] =
        s.compare.empty()
            ? nullptr
            : std::make_unique<Accumulation>(renderSettingsFor(s, s.compare, threads_, &control_));
    plan = std::make_unique<PassScheduler>(s.equal, acc[1] != nullptr, acc[0]->progressive(),
                                           acc[1] && acc[1]->progressive(), s.maxSpp);
    if (errors_) errors_->clear();
}

// Publishes the images a pass changed; returns whether the error is due for
// measuring (then both images exist and fit the reference).
bool ViewSession::publish(uint64_t generation, const Pass& pass,
                          const std::unique_ptr<Accumulation> (&acc)[2]) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (generation != frame_.generation || restart_) return false;
    if (pass.target[0]) frame_.a = std::make_shared<const Image>(acc[0]->image());
    if (pass.target[1]) frame_.b = std::make_shared<const Image>(acc[1]->image());
    frame_.spp = acc[0]->spp();
    frame_.sppB = acc[1] ? acc[1]->spp() : 0;
    renderSeconds_ = acc[0]->seconds() + (acc[1] ? acc[1]->seconds() : 0);
    paths_ = acc[0]->paths() + (acc[1] ? acc[1]->paths() : 0);
    changed_.notify_all();
    const bool complete = frame_.a && (!acc[1] || frame_.b);
    return complete && errors_ && errors_->due(std::max(frame_.spp, frame_.sppB)) &&
           referenceFits(acc[0]->image());
}

// Outside the lock: ꟻLIP takes a while, and only the worker uses errors_.
void ViewSession::measureError(uint64_t generation, const std::unique_ptr<Accumulation> (&acc)[2]) {
    errors_->measure(acc[0]->spp(), acc[0]->image(), acc[1] ? acc[1]->spp() : 0,
                     acc[1] ? &acc[1]->image() : nullptr);
    std::lock_guard<std::mutex> lock(mutex_);
    if (generation == frame_.generation) errorPoints_ = errors_->points();
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
    frame_ = Frame{nullptr, nullptr, 0, 0, frame_.generation + 1};
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
    s.sppB = frame_.sppB;
    if (frame_.a) s.width = frame_.a->width, s.height = frame_.a->height;
    s.pathsPerSecond = renderSeconds_ > 0 ? double(paths_) / renderSeconds_ : 0;
    s.elapsed = std::chrono::duration<double>(Clock::now() - started_).count();
    const bool complete = frame_.spp >= settings_.maxSpp &&
                          (settings_.compare.empty() || frame_.sppB >= settings_.maxSpp);
    s.running = !settings_.paused && error_.empty() && !complete;
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
