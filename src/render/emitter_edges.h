// The pixels that the outline of a directly visible emitter crosses.
//
// In such a pixel the box-filtered integrand of the camera dimensions is a step
// between the emitter and whatever lies beside it, often two orders of
// magnitude apart, so its error is decided by how the sampler places points in
// the pixel (dimensions 0 and 1) and little else; everywhere else the error is
// that of the light transport. A study reports the MSE of the two regions
// apart (docs/study-output.md): on the Cornell box the few hundred pixels along
// the light's outline hold most of independent sampling's error.
#pragma once

#include <cstdint>
#include <vector>

#include "render/render_scene.h"

namespace pathlab {

// A mask of the image (row-major, 1 = edge pixel) as seen through the scene's
// camera at `resolution` — the image a render at that resolution produces:
// the film's crop of it when the scene has a crop window. A camera with a
// thin lens is probed through the lens centre. A camera ray "sees an emitter" when its first hit is
// an area light whose emission faces it. Each pixel is probed on its outline,
// `perSide` equally spaced points per side (shared with its neighbours), and at
// its centre; it is an edge pixel when the probes disagree. An outline that
// crosses the pixel crosses its boundary twice, so it is found unless it cuts
// off a corner within about 1/perSide of a pixel, or an emitter lies wholly
// inside the pixel between probes. Deterministic: the same mask for any thread
// count.
std::vector<uint8_t> emitterEdgePixels(const RenderScene& scene, Vec2i resolution,
                                       int perSide = 32);

}  // namespace pathlab
