#include "view/view_session.h"

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "render/accumulation.h"
#include "scene/embree_accel.h"
#include "scene/loader.h"
#include "study/reference_cache.h"

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
    s.spectral = v.spectral;
    s.threads = threads;
    s.control = control;
    return s;
}

}  // namespace

std::shared_ptr<const RenderScene> loadViewScene(const std::string& scene,
                                                 const std::string& lightSampler) {
    SceneDescription description = loadScene(scene);
    // As `pathlab render --light-sampler`: the choice is made when the
    // render scene is built (its light tree or power table).
    if (!lightSampler.empty()) description.defaults.lightSampler = lightSampler;
    return std::make_shared<const RenderScene>(std::move(description));
}

ViewSession::ViewSession(ViewSettings settings, std::shared_ptr<const RenderScene> scene,
                         int threads, std::shared_ptr<const Image> reference)
    : settings_(std::move(settings)), scene_(std::move(scene)), threads_(threads) {
    validateViewSettings(settings_);
    if (reference) {
        // A file given by the user: known to show the scene at its size only.
        errors_ = std::make_shared<ErrorHistory>(std::move(reference));
        referenceTarget_ = {settings_.scene,
                            {errors_->reference().width, errors_->reference().height}};
        referenceTarget_.lightSampler = settings_.lightSampler;
        referenceTarget_.spectral = settings_.spectral;
        referenceSource_ = "file";
    }
    requestRestartLocked();  // generation 1; no other thread yet
    // Before the first pass: a short render could otherwise finish unmeasured.
    if (!errors_) lookUpReference();
    worker_ = std::thread([this] { work(); });
}

ViewSession::~ViewSession() {
    {
        std::lock_guard<std::mutex> lock(builderMutex_);
        builder_.reset();  // its callback takes mutex_: not held here
    }
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
        if (const auto errors = publish(generation, pass, acc))
            measureError(generation, *errors, acc);
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

// Publishes the images a pass changed; returns the error history when it is
// due for measuring (then both images exist and fit the reference).
std::shared_ptr<ErrorHistory> ViewSession::publish(uint64_t generation, const Pass& pass,
                                                   const std::unique_ptr<Accumulation> (&acc)[2]) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (generation != frame_.generation || restart_) return nullptr;
    if (pass.target[0]) frame_.a = std::make_shared<const Image>(acc[0]->image());
    if (pass.target[1]) frame_.b = std::make_shared<const Image>(acc[1]->image());
    frame_.spp = acc[0]->spp();
    frame_.sppB = acc[1] ? acc[1]->spp() : 0;
    renderSeconds_ = acc[0]->seconds() + (acc[1] ? acc[1]->seconds() : 0);
    paths_ = acc[0]->paths() + (acc[1] ? acc[1]->paths() : 0);
    changed_.notify_all();
    const bool complete = frame_.a && (!acc[1] || frame_.b);
    if (complete && errors_ && errors_->due(std::max(frame_.spp, frame_.sppB)) &&
        referenceFits(acc[0]->image()))
        return errors_;
    return nullptr;
}

// Outside the lock: ꟻLIP takes a while, and only the worker uses errors_.
void ViewSession::measureError(uint64_t generation, ErrorHistory& errors,
                               const std::unique_ptr<Accumulation> (&acc)[2]) {
    errors.measure(acc[0]->spp(), acc[0]->image(), acc[1] ? acc[1]->spp() : 0,
                   acc[1] ? &acc[1]->image() : nullptr);
    std::lock_guard<std::mutex> lock(mutex_);
    if (generation == frame_.generation && &errors == errors_.get()) errorPoints_ = errors.points();
}

// Called with the lock held. A file given by the user fits its scene at its
// size; a cached or built one also needs the depth and roulette it was
// rendered with.
bool ViewSession::referenceFits(const Image& image) const {
    if (!errors_ || errors_->reference().width != image.width ||
        errors_->reference().height != image.height)
        return false;
    if (referenceSource_ == "file") return settings_.scene == referenceTarget_.scene;
    return targetLocked() == referenceTarget_;
}

// Called with the lock held: what a reference for the current settings shows.
ReferenceTarget ViewSession::targetLocked() const {
    const Vec2i size = settings_.size.x > 0 ? settings_.size : scene_->description().resolution;
    return {settings_.scene,        size,
            settings_.maxDepth,     settings_.russianRoulette,
            settings_.lightSampler, settings_.spectral};
}

std::vector<float> ViewSession::errorMap(const Image& image, ErrorMapKind kind) const {
    std::shared_ptr<const ErrorHistory> errors;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!referenceFits(image)) return {};
        errors = errors_;
    }
    return errors->errorMap(image, kind);  // reads only the reference
}

// The study's cache, searched when the current reference does not fit the
// settings: the entry for them with the most samples, if there is one.
void ViewSession::lookUpReference() {
    std::shared_ptr<const RenderScene> scene;
    ReferenceTarget target;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (currentReferenceFitsLocked()) return;
        scene = scene_, target = targetLocked();
    }
    std::optional<FoundReference> found =
        findCachedReference(ReferenceCache::standard(), *scene, target);
    if (!found) return;
    useReference(std::make_shared<const Image>(std::move(found->reference.image)), target, "cache",
                 found->spp, /*unlessOneFits=*/true);
}

bool ViewSession::currentReferenceFitsLocked() const {
    return errors_ && (referenceSource_ == "file" || referenceTarget_ == targetLocked());
}

// Replaces the reference; the worker measures against it from its next pass.
void ViewSession::useReference(std::shared_ptr<const Image> image, const ReferenceTarget& target,
                               const std::string& source, int spp, bool unlessOneFits) {
    auto errors = std::make_shared<ErrorHistory>(std::move(image));  // prepares ꟻLIP: outside
    std::lock_guard<std::mutex> lock(mutex_);
    if (unlessOneFits && currentReferenceFitsLocked()) return;
    errors_ = std::move(errors);
    referenceTarget_ = target, referenceSource_ = source, referenceSpp_ = spp;
    errorPoints_.clear();
}

void ViewSession::buildReference(int spp) {
    if (spp < 1 || spp > (1 << 24))
        throw InputError("reference spp must be between 1 and 16777216, got " +
                         std::to_string(spp));
    std::shared_ptr<const RenderScene> scene;
    ReferenceTarget target;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        scene = scene_, target = targetLocked();
        referenceError_.clear();
    }
    const auto done = [this, target, spp](std::shared_ptr<const Image> image,
                                          const std::string& error) {
        if (image) return useReference(std::move(image), target, "page", spp);
        std::lock_guard<std::mutex> lock(mutex_);
        referenceError_ = error;
    };
    std::lock_guard<std::mutex> lock(builderMutex_);
    builder_.reset();  // cancels one under way: its callback then does not run
    builder_ = std::make_unique<ReferenceBuilder>(scene, target, spp, threads_, done);
}

void ViewSession::waitForReference() const {
    for (;;) {
        {
            std::lock_guard<std::mutex> lock(builderMutex_);
            if (!builder_ || builder_->finished()) return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
}

std::vector<ErrorPoint> ViewSession::errorPoints() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return errorPoints_;
}

SessionStatus ViewSession::update(const nlohmann::json& changes) {
    std::unique_lock<std::mutex> lock(mutex_);
    ViewSettings next = applySettingsJson(settings_, changes);
    std::shared_ptr<const RenderScene> scene = scene_;
    if (next.scene != settings_.scene || next.lightSampler != settings_.lightSampler) {
        lock.unlock();  // loading may take a while; the render goes on meanwhile
        scene = loadViewScene(next.scene, next.lightSampler);
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
    if (restart) lookUpReference();
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
    std::unique_lock<std::mutex> lock(mutex_);
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
    if (s.reference) s.referenceSource = referenceSource_, s.referenceSpp = referenceSpp_;
    s.referenceError = referenceError_;
    lock.unlock();
    std::lock_guard<std::mutex> building(builderMutex_);
    if (builder_ && !builder_->finished()) s.referenceProgress = builder_->progress();
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
