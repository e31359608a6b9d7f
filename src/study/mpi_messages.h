// The messages between the ranks of a study run across MPI (docs/cluster.md,
// "Message flow"), as bytes: a cell render handed to a rank, the measurements
// it sends back, and a scene's reference sent to every rank. Numbers travel
// as their bytes, so every metric arrives bit for bit as it was computed.
#pragma once

#include <vector>

#include "core/image.h"
#include "study/runner_steps.h"

namespace pathlab {

// MPI tags of the point-to-point messages.
enum MpiStudyTag : int {
    kTagReady = 1,   // worker → rank 0: no payload; the worker wants a render
    kTagResult = 2,  // worker → rank 0: the measured cells of its last render
    kTagFailed = 3,  // worker → rank 0: why its last render failed (text)
    kTagRender = 4,  // rank 0 → worker: one render (a scene index and a CellRender)
    kTagStop = 5,    // rank 0 → worker: no payload; nothing left to do
};

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
