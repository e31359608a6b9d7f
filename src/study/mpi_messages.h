// The messages between the ranks of a study run across MPI (docs/cluster.md,
// "Message flow"), as bytes: a cell render handed to a rank, the measurements
// it sends back, and a scene's reference sent to every rank. Numbers travel
// as their bytes, so every metric arrives bit for bit as it was computed.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"
#include "study/reference_ranges.h"
#include "study/runner_steps.h"

namespace pathlab {

// MPI tags of the point-to-point messages.
enum MpiStudyTag : int {
    kTagReady = 1,   // worker → rank 0: no payload; the worker wants a render
    kTagResult = 2,  // worker → rank 0: the measured cells of its last render
    kTagFailed = 3,  // worker → rank 0: why its last render failed (text)
    kTagRender = 4,  // rank 0 → worker: one render (a scene index and a CellRender)
    kTagStop = 5,    // rank 0 → worker: no payload; nothing left to do
    kTagRange = 6,   // rank 0 → worker: one sample range of a reference (RangeTask)
    kTagSums = 7,    // worker → rank 0: that range's running sums
};

// Range `index` of the reference of scene `scene` (referenceRanges).
struct RangeTask {
    int scene = 0;
    int index = 0;
    bool operator==(const RangeTask&) const = default;
};

std::vector<char> encodeRangeTask(const RangeTask& task);
RangeTask decodeRangeTask(const std::vector<char>& bytes);

// A rendered range: the scene's index, then the bytes of its range file
// (encodeRangeSums, which carry the reference's cache key).
std::vector<char> encodeRangeResult(int scene, const RangeSums& range, const std::string& cacheKey);
// Throws std::runtime_error for bytes of another reference or truncated ones.
RangeSums decodeRangeResult(const std::vector<char>& bytes, int& scene,
                            const std::vector<std::string>& cacheKeys);

struct RenderTask {
    int scene = 0;  // index into the spec's scenes
    study_steps::CellRender cells;
};

std::vector<char> encodeTask(const RenderTask& task);
RenderTask decodeTask(const std::vector<char>& bytes);

// The metrics of each cell (not FLIP's per-pixel map, which only the images need).
std::vector<char> encodeMeasured(const std::vector<study_steps::MeasuredCell>& cells);
std::vector<study_steps::MeasuredCell> decodeMeasured(const std::vector<char>& bytes);

// A reference's pixels and viewing exposure: what a rank needs to measure cells.
std::vector<char> encodeReferenceImage(const Image& image, float exposure);
void decodeReferenceImage(const std::vector<char>& bytes, Image& image, float& exposure);

}  // namespace pathlab
