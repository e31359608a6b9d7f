// A reference, the longest render of a study, is rendered as a fixed list of
// sample ranges (RenderSettings::sampleRange): each range's per-pixel running
// sums are kept in a file of its own as soon as it is done, and the reference
// is the ranges' sums added in range order. The list depends on the
// reference's spp only, so one process, or any number of MPI ranks sharing
// the ranges out, make the same reference bit for bit; a study killed while
// rendering it keeps its finished ranges.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "render/render_scene.h"
#include "render/running_sums.h"
#include "study/reference_cache.h"
#include "study/spec.h"

namespace pathlab {

// Ranges hold at least this many samples and start on a multiple of it (the
// renderer's batch of samples per pixel), and a reference has at most
// kMaxReferenceRanges of them: enough to share a 4096-spp reference among 16
// ranks, few enough that the ranges' files (48 bytes a pixel each, 120 with
// a filter of varying weights) stay a small multiple of the image.
// Changing either changes every reference's bits: bump kReferenceCacheVersion.
inline constexpr int kMinReferenceRangeSpp = 64;
inline constexpr int kMaxReferenceRanges = 16;

// The ranges of a reference of `spp` samples per pixel: consecutive, from 0
// to spp, equal but for a shorter last one. `count` = 0 chooses them as
// above; a spec's `[reference] ranges` = N (≤ spp) asks for N ranges of
// ⌈spp / N⌉ samples (fewer when the last ones would be empty), for clusters
// with more ranks than 16 ranges can keep busy (docs/cluster.md).
std::vector<SampleRange> referenceRanges(int spp, int count = 0);

// One finished range: its index in referenceRanges, its sums, and the
// seconds its render took.
struct RangeSums {
    int index = 0;
    RunningSums sums;
    double seconds = 0;
};

// A range's file and message bytes: the reference's cache key, the range,
// then the sums' doubles as they are. Decoding throws std::runtime_error for
// bytes of another format or truncated ones.
std::string encodeRangeSums(const RangeSums& range, const std::string& cacheKey);
RangeSums decodeRangeSums(std::string_view bytes, const std::string& cacheKey);

// The finished ranges of one reference, as files beside the reference cache's
// entries: DIRECTORY/KEY.range-I-of-N.sums, each written atomically.
class ReferenceRangeFiles {
  public:
    ReferenceRangeFiles(std::filesystem::path directory, std::string cacheKey, int spp,
                        int count = 0);

    const std::vector<SampleRange>& ranges() const { return ranges_; }
    const std::string& cacheKey() const { return cacheKey_; }
    // Indices of the ranges without a file, ascending.
    std::vector<int> missing() const;
    // Nullopt when absent, damaged, or not that range of this reference.
    std::optional<RangeSums> load(int index) const;
    void save(const RangeSums& range) const;
    void removeAll() const;
    std::filesystem::path path(int index) const;

  private:
    std::filesystem::path directory_;
    std::string cacheKey_;
    std::vector<SampleRange> ranges_;
};

// The range files of a scene's reference in the standard cache.
ReferenceRangeFiles referenceRangeFiles(const ReferenceCache& cache, const std::string& cacheKey,
                                        const StudySpec& spec);

// Renders range `index` of the scene's reference with `threads` (0 = all
// cores); `control` (optional) reports its tiles and may cancel it.
RangeSums renderReferenceRange(const RenderScene& scene, const StudySpec& spec, int threads,
                               int index, RenderControl* control = nullptr);

// The reference from all its ranges, added in range order; a range whose
// file is missing or damaged is rendered by `renderMissing` first. Its noise
// floor over the image and each region of `edgeMask`, and its exposure, as
// renderReference measures them; `seconds` is the sum of the ranges'.
Reference mergeReferenceRanges(const RenderScene& scene, const StudySpec& spec,
                               const ReferenceRangeFiles& files,
                               const std::function<RangeSums(int)>& renderMissing,
                               const std::vector<uint8_t>& edgeMask);

}  // namespace pathlab
