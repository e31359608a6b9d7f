// The camera samples of up to kCameraPacketSamples consecutive samples of a
// pixel: where each lands on the film, the ray it starts, and its filter
// weight — pbrt-v4's GetCameraSample and Camera::GenerateRay, drawn a lane of
// samples at a time from the dimensions sampling/sampler.h lays out.
//
// The classic pinhole with the box filter of radius ½ (every pathlab scene)
// takes exactly the arithmetic the renderer always had: the film position is
// pixel + u, the direction PinholeCamera::direction of it, the weight 1.
#pragma once

#include "render/camera_model.h"
#include "render/pixel_filter.h"
#include "sampling/sampler.h"

namespace pathlab {

// Samples first … first + count − 1 of `pixel` (full-image coordinates):
// their rays (origins[k], unit dirs[k]) and filter weights. Draws dimensions
// 0 and 1 (the film position, through drawPixelLanes) and, for a camera with a
// thin lens, 2 and 3 (the lens position) — nothing else.
template <Sampler S>
void drawCameraSamples(const CameraModel& camera, const FilterSampler& filter, S& sampler,
                       Vec2i pixel, int first, int count, Vec3f* origins, Vec3f* dirs,
                       float* weights) {
    // Every lane's index is set (those past count are never drawn).
    int indices[kCameraPacketSamples];
    for (int k = 0; k < kCameraPacketSamples; ++k) indices[k] = first + k;
    Vec2f u[kCameraPacketSamples], film[kCameraPacketSamples];
    drawPixelLanes(sampler, pixel, indices, count, u);
    if (filter.unitBox()) {
        for (int k = 0; k < count; ++k)
            film[k] = {float(pixel.x) + u[k].x, float(pixel.y) + u[k].y}, weights[k] = 1;
    } else {
        // pbrt-v4: pFilm = pPixel + filter offset + (½, ½).
        for (int k = 0; k < count; ++k) {
            const FilterSample fs = filter.sample(u[k]);
            film[k] = {float(pixel.x) + fs.p.x + 0.5f, float(pixel.y) + fs.p.y + 0.5f};
            weights[k] = fs.weight;
        }
    }
    if (camera.isPinhole()) {
        const PinholeCamera& c = camera.pinhole();
        for (int k = 0; k < count; ++k)
            origins[k] = c.eye(), dirs[k] = c.direction(film[k].x, film[k].y);
        return;
    }
    const ProjectiveCamera& c = camera.projective();
    Vec2f uLens[kCameraPacketSamples];
    if (c.hasLens())
        drawLanes2D(sampler, pixel, indices, count, dims::kLens, uLens);
    else
        for (int k = 0; k < count; ++k) uLens[k] = {0.5f, 0.5f};
    for (int k = 0; k < count; ++k) {
        const CameraRay r = c.ray(film[k], uLens[k]);
        origins[k] = r.origin, dirs[k] = r.direction;
    }
}

}  // namespace pathlab
