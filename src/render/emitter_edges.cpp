#include "render/emitter_edges.h"

#include <tbb/parallel_for.h>

#include <stdexcept>

#include "render/camera_model.h"
#include "render/film.h"

namespace pathlab {
namespace {

// Through the lens centre: the ray a pinhole at the lens would trace.
bool seesEmitter(const RenderScene& scene, const CameraModel& camera, float x, float y) {
    const CameraRay r = camera.centralRay({x, y});
    SurfaceInteraction si;
    if (!scene.intersect(r.origin, r.direction, &si) || si.light < 0) return false;
    return !isBlack(scene.lights().areaLight(si.light).emittedAt(si.p, -r.direction));
}

// Probes along `lines` straight lines of the film, `count` points each:
// probe(line, k) gives the film position of point k of that line.
template <class Position>
std::vector<uint8_t> probeLines(const RenderScene& scene, const CameraModel& camera, int lines,
                                int count, Position position) {
    std::vector<uint8_t> hit(size_t(lines) * size_t(count));
    tbb::parallel_for(0, lines, [&](int line) {
        for (int k = 0; k < count; ++k) {
            const Vec2f p = position(line, k);
            hit[size_t(line) * size_t(count) + size_t(k)] = seesEmitter(scene, camera, p.x, p.y);
        }
    });
    return hit;
}

}  // namespace

std::vector<uint8_t> emitterEdgePixels(const RenderScene& scene, Vec2i resolution, int perSide) {
    if (resolution.x <= 0 || resolution.y <= 0 || perSide <= 0)
        throw std::invalid_argument("emitterEdgePixels: empty image or no probes");
    // The pixels the render produces: the film's crop of the full image.
    const PixelBounds bounds = filmPixelBounds(scene.description().film, resolution);
    const int w = bounds.width(), h = bounds.height(), n = perSide;
    const int x0 = bounds.min.x, y0 = bounds.min.y;
    const CameraModel camera(scene.description().camera, resolution);
    const float step = 1.0f / float(n);
    // Vertical lines x = 0 … w, horizontal lines y = 0 … h, pixel centres
    // (of the image; + x0, y0 on the full film).
    const auto vertical = probeLines(scene, camera, w + 1, h * n, [&](int x, int k) {
        return Vec2f{float(x0 + x), float(y0) + (float(k) + 0.5f) * step};
    });
    const auto horizontal = probeLines(scene, camera, h + 1, w * n, [&](int y, int k) {
        return Vec2f{float(x0) + (float(k) + 0.5f) * step, float(y0 + y)};
    });
    const auto centre = probeLines(scene, camera, h, w, [&](int y, int x) {
        return Vec2f{float(x0 + x) + 0.5f, float(y0 + y) + 0.5f};
    });
    std::vector<uint8_t> edge(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const uint8_t first = centre[size_t(y) * size_t(w) + size_t(x)];
            bool differs = false;
            for (int k = 0; k < n && !differs; ++k) {
                const size_t along = size_t(y) * size_t(n) + size_t(k);
                const size_t across = size_t(x) * size_t(n) + size_t(k);
                differs = vertical[size_t(x) * size_t(h * n) + along] != first ||
                          vertical[size_t(x + 1) * size_t(h * n) + along] != first ||
                          horizontal[size_t(y) * size_t(w * n) + across] != first ||
                          horizontal[size_t(y + 1) * size_t(w * n) + across] != first;
            }
            edge[size_t(y) * size_t(w) + size_t(x)] = differs;
        }
    }
    return edge;
}

}  // namespace pathlab
