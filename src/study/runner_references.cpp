// The study's references: found in the cache or the study directory, else
// rendered range by range (reference_ranges.h) and merged, then cached.
#include <cmath>

#include "core/atomic_file.h"
#include "core/error.h"
#include "study/reference_ranges.h"
#include "study/runner_steps.h"

namespace pathlab::study_steps {
namespace fs = std::filesystem;
namespace {

std::string referenceLabel(const SceneJob& job, const StudySpec& spec) {
    return job.scene.name + " (" + std::to_string(spec.reference.spp) + " spp " +
           spec.reference.sampler + ", " + std::to_string(spec.resolution.x) + "x" +
           std::to_string(spec.resolution.y) + ")";
}

ReferenceRangeFiles rangeFilesOf(const SceneJob& job, const StudySpec& spec) {
    return referenceRangeFiles(ReferenceCache::standard(), job.cacheKey, spec);
}

}  // namespace

std::string rangeLabel(const SceneJob& job, const StudySpec& spec, int index) {
    const std::vector<SampleRange> ranges =
        referenceRanges(spec.reference.spp, spec.reference.ranges);
    const SampleRange& r = ranges.at(size_t(index));
    return job.scene.name + " reference samples " + std::to_string(r.first) + "…" +
           std::to_string(r.end - 1) + " (range " + std::to_string(index + 1) + " of " +
           std::to_string(ranges.size()) + ")";
}

std::optional<Reference> findReference(const SceneJob& job, StudyContext& ctx) {
    const ReferenceCache cache = ReferenceCache::standard();
    const std::string what = referenceLabel(job, ctx.spec);
    // An entry's region floors were measured over the mask it was rendered
    // with; one whose edge count differs is from another mask: rendered again.
    if (auto cached = cache.load(job.cacheKey); cached && cached->edgePixels == job.edgePixels) {
        ctx.progress.message("reference: cached " + what);
        ++ctx.run.referencesReused;
        return cached;
    }
    const fs::path own = ctx.options.dir / "references" / (job.scene.name + ".exr");
    for (const ReferenceRow& row : ctx.store.references()) {
        if (row.scene != job.scene.name || row.cacheKey != job.cacheKey) continue;
        if (row.edgePixels != job.edgePixels || !row.noiseMseRest) break;  // an older study
        if (!fs::is_regular_file(own)) break;
        ctx.progress.message("reference: from the study directory " + what);
        Reference r{readImage(own.string()),
                    row.seconds,
                    {row.noiseMse, row.noiseRelmse, row.noiseMseEdge, row.noiseMseRest},
                    float(row.exposure),
                    row.cacheKey,
                    job.edgePixels};
        cache.store(r, job.scene, ctx.spec);
        ++ctx.run.referencesReused;
        return r;
    }
    return std::nullopt;
}

std::vector<int> missingReferenceRanges(const SceneJob& job, StudyContext& ctx) {
    const ReferenceRangeFiles files = rangeFilesOf(job, ctx.spec);
    // What a killed run was writing: never complete, so never used.
    removeStaleTemporaries(ReferenceCache::standard().directory());
    const std::vector<int> missing = files.missing();
    const size_t kept = files.ranges().size() - missing.size();
    ctx.progress.message("rendering reference: " + referenceLabel(job, ctx.spec) + " in " +
                         std::to_string(files.ranges().size()) + " sample ranges" +
                         (kept ? ", " + std::to_string(kept) + " already done" : ""));
    return missing;
}

void saveReferenceRange(const SceneJob& job, const RangeSums& range, StudyContext& ctx) {
    rangeFilesOf(job, ctx.spec).save(range);
    ctx.progress.addWorkDone(pixels(ctx.spec) * range.sums.spp);
}

Reference finishReference(const SceneJob& job, StudyContext& ctx) {
    const ReferenceRangeFiles files = rangeFilesOf(job, ctx.spec);
    // Every range is saved before it is merged, so a failure later loses none.
    const auto renderMissing = [&](int index) {
        RangeSums range = renderReferenceRange(*job.render, ctx.spec, ctx.options.threads, index);
        saveReferenceRange(job, range, ctx);
        return range;
    };
    Reference r = mergeReferenceRanges(*job.render, ctx.spec, files, renderMissing, job.edgeMask);
    ReferenceCache::standard().store(r, job.scene, ctx.spec);
    files.removeAll();  // the cache entry holds it all now
    ++ctx.run.referencesRendered;
    return r;
}

// From the cache, else from this study's own copy (a resumed study whose
// cache was cleared), else rendered — and cached for the studies to come.
Reference obtainReference(const SceneJob& job, StudyContext& ctx) {
    if (std::optional<Reference> found = findReference(job, ctx)) return std::move(*found);
    for (int index : missingReferenceRanges(job, ctx)) {
        saveReferenceRange(
            job, renderReferenceRange(*job.render, ctx.spec, ctx.options.threads, index), ctx);
        ctx.progress.message("reference: rendered " + rangeLabel(job, ctx.spec, index));
    }
    return finishReference(job, ctx);
}

// The reference with its emitter-edge pixels painted cyan (full green and
// blue at the viewing exposure), for the report to show where they are.
Image withEdgeMarked(const Image& reference, const std::vector<uint8_t>& edgeMask, float exposure) {
    Image marked = reference;
    const float full = std::exp2(-exposure);  // 1 after the exposure is applied
    for (size_t i = 0; i < edgeMask.size(); ++i)
        if (edgeMask[i])
            marked.set(int(i % size_t(marked.width)), int(i / size_t(marked.width)),
                       Vec3f(0, full, full));
    return marked;
}

void recordReference(const SceneJob& job, const Reference& ref, StudyContext& ctx) {
    const std::string stem = "references/" + job.scene.name;
    writeImage((ctx.options.dir / (stem + ".exr")).string(), ref.image);
    writeImage((ctx.options.dir / (stem + ".png")).string(), ref.image, ref.exposure);
    writeImage((ctx.options.dir / (stem + "-edge.png")).string(),
               withEdgeMarked(ref.image, job.edgeMask, ref.exposure), ref.exposure);
    ctx.store.putReference({job.scene.name, ctx.spec.reference.sampler, ctx.spec.reference.spp,
                            ref.seconds, ref.cacheKey, ref.noise.mse, ref.noise.relmse,
                            ref.exposure, stem + ".exr", ref.noise.mseEdge, ref.noise.mseRest,
                            ref.edgePixels});
}

}  // namespace pathlab::study_steps
