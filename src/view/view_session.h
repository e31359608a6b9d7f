// The accumulation a `pathlab view` server shows: a worker thread renders
// passes of sampler A (and B, at equal spp, with --compare) and publishes the
// image after each. Render settings restart it; display settings, pause and
// the HTTP threads reading frames do not disturb it.
#pragma once

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/image.h"
#include "render/accumulation.h"
#include "render/renderer.h"
#include "view/error_history.h"
#include "view/reference_builder.h"
#include "view/reference_lookup.h"
#include "view/view_settings.h"

namespace pathlab::view {

// The images after a finished pass; shared, never changed once published.
struct Frame {
    std::shared_ptr<const Image> a, b;  // b: null without a compare sampler (or before its pass)
    int spp = 0;                        // A's
    int sppB = 0;                       // B's: spp at equal spp, its own count at equal time
    uint64_t generation = 0;            // increments on every restart
};

struct SessionStatus {
    ViewSettings settings;
    int spp = 0, sppB = 0, width = 0, height = 0;  // sppB: Frame's
    double pathsPerSecond = 0;      // both samplers' paths over render time since the restart
    double elapsed = 0;             // wall seconds since the restart
    bool reference = false;         // is the error against a reference measured?
    std::string referenceSource;    // "file", "cache" or "page"; "" without one
    int referenceSpp = 0;           // of a cached or page-built one; 0: unknown
    double referenceProgress = -1;  // of one being built, 0 … 1; −1: none
    std::string referenceError;     // why the last build failed
    bool running = false;           // neither paused nor at max_spp
    uint64_t generation = 0;
    std::string error;  // a render that failed (then running is false)
};

// The scene a settings object names, loaded (InputError when it cannot be),
// choosing its lights by `lightSampler` ("": the scene file's own choice).
std::shared_ptr<const RenderScene> loadViewScene(const std::string& scene,
                                                 const std::string& lightSampler = "");

class ViewSession {
  public:
    // Starts rendering at once. `scene` is settings.scene, loaded. With a
    // `reference` (linear RGB), the error of A and B against it is measured
    // at log-spaced spp (ErrorHistory) while the scene is that first one and
    // the image has the reference's size. Without one, and whenever the
    // render settings change, the study's reference cache is searched for a
    // reference of the scene and settings (reference_lookup.h).
    ViewSession(ViewSettings settings, std::shared_ptr<const RenderScene> scene, int threads = 0,
                std::shared_ptr<const Image> reference = nullptr);
    ~ViewSession();  // stops the worker
    ViewSession(const ViewSession&) = delete;
    ViewSession& operator=(const ViewSession&) = delete;

    // Applies a JSON object of settings (view_settings.h). Loads a new scene
    // before anything changes; throws InputError and changes nothing when a
    // value is bad. A change of render settings restarts accumulation.
    SessionStatus update(const nlohmann::json& changes);
    void reset();  // starts accumulation over with the same settings
    Frame frame() const;
    SessionStatus status() const;
    // Blocks until a pass of at least `spp` of the current generation is
    // published (or the session stops); for tests and benchmarks.
    Frame waitForSpp(int spp) const;
    // The error measured so far in this generation (empty without a reference).
    std::vector<ErrorPoint> errorPoints() const;
    // The error map of `image` (one of a frame's) against the reference, or
    // an empty vector when there is no reference for it.
    std::vector<float> errorMap(const Image& image, ErrorMapKind kind) const;
    // Blocks until the worker waits for work (paused, done, failed).
    void waitUntilIdle() const;
    // Starts rendering a reference of `spp` for the current settings in the
    // background (cancelling one under way), stored in the study's cache;
    // the live error starts when it is done. Throws InputError for a bad spp.
    void buildReference(int spp);
    // Blocks until no reference is being built; for tests.
    void waitForReference() const;

  private:
    void work();
    void startLocked(std::unique_ptr<Accumulation> (&acc)[2], std::unique_ptr<PassScheduler>& plan);
    std::shared_ptr<ErrorHistory> publish(uint64_t generation, const Pass& pass,
                                          const std::unique_ptr<Accumulation> (&acc)[2]);
    void measureError(uint64_t generation, ErrorHistory& errors,
                      const std::unique_ptr<Accumulation> (&acc)[2]);
    bool referenceFits(const Image& image) const;
    void requestRestartLocked();
    ReferenceTarget targetLocked() const;
    void lookUpReference();
    // unlessOneFits: a cache lookup's result, dropped if a reference for the
    // settings arrived while the lookup ran (a page build finishing).
    void useReference(std::shared_ptr<const Image> image, const ReferenceTarget& target,
                      const std::string& source, int spp, bool unlessOneFits = false);
    bool currentReferenceFitsLocked() const;

    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    ViewSettings settings_;
    std::shared_ptr<const RenderScene> scene_;
    int threads_;
    bool stopping_ = false, restart_ = false, idle_ = false;
    std::string error_;  // why the last pass failed; rendering waits for new settings
    Frame frame_;
    double renderSeconds_ = 0;
    uint64_t paths_ = 0;
    std::chrono::steady_clock::time_point started_;
    RenderControl control_;
    // The reference's error history: replaced whole when a reference comes
    // (never changed by other threads than the worker, which measures).
    std::shared_ptr<ErrorHistory> errors_;
    ReferenceTarget referenceTarget_;  // what it shows
    std::string referenceSource_, referenceError_;
    int referenceSpp_ = 0;
    mutable std::mutex builderMutex_;  // never taken inside mutex_'s hold
    std::unique_ptr<ReferenceBuilder> builder_;
    std::vector<ErrorPoint> errorPoints_;  // errors_'s, published
    std::thread worker_;
};

}  // namespace pathlab::view
