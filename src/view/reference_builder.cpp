#include "view/reference_builder.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include "render/emitter_edges.h"
#include "study/reference_ranges.h"

namespace pathlab::view {

ReferenceBuilder::ReferenceBuilder(std::shared_ptr<const RenderScene> scene, ReferenceTarget target,
                                   int spp, int threads, Done done)
    : scene_(std::move(scene)),
      target_(std::move(target)),
      spp_(spp),
      threads_(threads),
      rangeCount_(int(referenceRanges(spp).size())),
      done_(std::move(done)) {
    thread_ = std::thread([this] { run(); });
}

ReferenceBuilder::~ReferenceBuilder() {
    control_.cancel = true;
    thread_.join();
}

double ReferenceBuilder::progress() const {
    if (finished_) return 1;
    const size_t total = control_.tilesTotal;
    const double partial = total ? double(control_.tilesDone) / double(total) : 0;
    return std::min(1.0, (rangesDone_ + partial) / rangeCount_);
}

void ReferenceBuilder::run() {
    // Linux keeps a nice value per thread: only this one yields to the view.
    setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), 19);
    std::shared_ptr<const Image> image;
    std::string error;
    try {
        // Workers serve arenas of higher priority first: the view's passes.
        tbb::task_arena arena(tbb::task_arena::automatic, 1, tbb::task_arena::priority::low);
        arena.execute([&] { image = build(); });
    } catch (const RenderCancelled&) {
        error = "cancelled";
    } catch (const std::exception& e) {
        error = e.what();
    }
    // Finished only once the session holds the result: who waits for the
    // build then sees the page's reference, not a cache lookup racing it.
    if (!control_.cancel) done_(image, error);
    finished_ = true;
}

// As a study's runner makes it (study/runner_references.cpp): the ranges not
// in the cache yet, each saved when done (a range a study left is reused, and
// one this leaves a study reuses), then merged and cached.
std::shared_ptr<const Image> ReferenceBuilder::build() {
    const StudySpec spec = referenceSpecFor(target_, spp_);
    const StudyScene source = studySceneOf(target_.scene);
    const ReferenceCache cache = ReferenceCache::standard();
    const std::string key = referenceCacheKey(scene_->description(), source, spec);
    const ReferenceRangeFiles files = referenceRangeFiles(cache, key, spec);
    const auto renderRange = [&](int index) {
        control_.tilesDone = 0, control_.tilesTotal = 0;
        RangeSums range = renderReferenceRange(*scene_, spec, threads_, index, &control_);
        files.save(range);
        ++rangesDone_;
        return range;
    };
    const std::vector<int> missing = files.missing();
    rangesDone_ = rangeCount_ - int(missing.size());
    for (int index : missing) renderRange(index);
    rangesDone_ = rangeCount_;
    const std::vector<uint8_t> edges = emitterEdgePixels(*scene_, spec.resolution);
    Reference r = mergeReferenceRanges(*scene_, spec, files, renderRange, edges);
    cache.store(r, source, spec);
    files.removeAll();
    return std::make_shared<const Image>(std::move(r.image));
}

}  // namespace pathlab::view
