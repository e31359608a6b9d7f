// A reference for `pathlab view`, rendered in the background the way a study
// renders its own — sample ranges saved as they finish, merged, stored in the
// study's reference cache (study/reference_ranges.h) — so the page gets its
// live error and a later study of the same scene and settings reuses the
// image instead of rendering it again. Its render tasks run in a TBB arena of
// low priority and its thread at the lowest CPU priority, so the view's own
// passes come first.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "core/image.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "view/reference_lookup.h"

namespace pathlab::view {

class ReferenceBuilder {
  public:
    // Called once from the builder's thread: the image, or null and why not.
    using Done = std::function<void(std::shared_ptr<const Image>, const std::string& error)>;

    // Starts at once; `threads` as the view's (0: all cores).
    ReferenceBuilder(std::shared_ptr<const RenderScene> scene, ReferenceTarget target, int spp,
                     int threads, Done done);
    ~ReferenceBuilder();  // cancels a render under way and waits for the thread
    ReferenceBuilder(const ReferenceBuilder&) = delete;
    ReferenceBuilder& operator=(const ReferenceBuilder&) = delete;

    const ReferenceTarget& target() const { return target_; }
    int spp() const { return spp_; }
    double progress() const;  // 0 … 1: the ranges done and the tiles of the one under way
    bool finished() const { return finished_; }

  private:
    void run();
    std::shared_ptr<const Image> build();

    std::shared_ptr<const RenderScene> scene_;
    ReferenceTarget target_;
    int spp_, threads_, rangeCount_;
    Done done_;
    RenderControl control_;
    std::atomic<int> rangesDone_{0};
    std::atomic<bool> finished_{false};
    std::thread thread_;
};

}  // namespace pathlab::view
