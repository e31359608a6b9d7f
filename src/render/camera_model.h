// The scene's camera as the renderer uses it: the classic pinhole of
// pathlab's own scenes (camera.h, unchanged to the bit), or a pbrt-v4 camera
// (Camera::pbrtFrame) — perspective or orthographic, optionally with a thin
// lens — generated with pbrt-v4's semantics (cameras.h / cameras.cpp:
// ProjectiveCamera, PerspectiveCamera::GenerateRay,
// OrthographicCamera::GenerateRay).
//
// pbrt-v4's spaces, in the order a film position travels:
//   raster  (0, 0) is the top-left corner of the full image, x right, y down,
//           in pixels (pbrt's rasterFromScreen maps the screen window's
//           (xmin, ymax) corner there and flips y);
//   screen  the screen window [xmin, xmax] × [ymin, ymax];
//   camera  x right, y up, z forward: a perspective ray through screen point
//           (sx, sy) has direction (sx·tan(fov/2), sy·tan(fov/2), 1), an
//           orthographic one starts at (sx, sy, 0) and runs along +z;
//   world   eye + x·axisX + y·axisY + z·axisZ (directions renormalised, since
//           the axes may carry a scale).
// The thin lens (Potmesil & Chakravarty 1981; pbrt-v4 book §5.2.3): the ray
// starts at lensRadius·(Shirley–Chiu concentric disk point of uLens) on the
// z = 0 plane and passes through the point where the pinhole ray meets the
// plane of focus z = focalDistance, so every lens position sees that point.
#pragma once

#include <optional>

#include "core/math.h"
#include "render/camera.h"
#include "scene/scene.h"

namespace pathlab {

struct CameraRay {
    Vec3f origin, direction;  // direction of unit length
};

// The screen window pbrt-v4 uses for this camera at this full resolution
// (xmin, xmax, ymin, ymax): the camera's own when it gives one, else
// [−a, a] × [−1, 1] for frame aspect ratio a > 1 and [−1, 1] × [−1/a, 1/a]
// otherwise (so the field of view spans the shorter side).
struct ScreenWindow {
    float xmin, xmax, ymin, ymax;
};
ScreenWindow pbrtScreenWindow(const Camera& camera, Vec2i fullResolution);

// pbrt-v4's PerspectiveCamera / OrthographicCamera for a pbrtFrame camera.
class ProjectiveCamera {
  public:
    ProjectiveCamera(const Camera& camera, Vec2i fullResolution);

    bool hasLens() const { return lensRadius_ > 0; }
    // Every ray starts at the eye (a perspective camera without a lens): the
    // camera rays of a pixel can go to Embree as one coherent packet.
    bool sharedOrigin() const { return perspective_ && !hasLens(); }
    Vec3f eye() const { return eye_; }

    // Screen coordinates of a raster position.
    Vec2f screenFromRaster(Vec2f raster) const {
        return {xmin_ + raster.x * screenPerPixelX_, ymax_ - raster.y * screenPerPixelY_};
    }
    // The ray through raster position `raster` and lens sample uLens ∈ [0,1)²
    // (ignored without a lens; (½, ½) is the lens centre), in camera space
    // and in world space.
    CameraRay cameraSpaceRay(Vec2f raster, Vec2f uLens) const;
    CameraRay ray(Vec2f raster, Vec2f uLens) const {
        const CameraRay c = cameraSpaceRay(raster, uLens);
        return {
            eye_ + axisX_ * c.origin.x + axisY_ * c.origin.y + axisZ_ * c.origin.z,
            normalize(axisX_ * c.direction.x + axisY_ * c.direction.y + axisZ_ * c.direction.z)};
    }

  private:
    bool perspective_;
    Vec3f eye_, axisX_, axisY_, axisZ_;
    float xmin_, ymax_, screenPerPixelX_, screenPerPixelY_;
    float tanHalfFov_;
    float lensRadius_, focalDistance_;
};

// Either camera, chosen by Camera::pbrtFrame. A classic camera ignores the
// pbrt fields (lensRadius included): its rays are PinholeCamera's.
class CameraModel {
  public:
    CameraModel(const Camera& camera, Vec2i fullResolution) {
        if (camera.pbrtFrame)
            projective_.emplace(camera, fullResolution);
        else
            pinhole_.emplace(camera, fullResolution);
    }
    bool isPinhole() const { return pinhole_.has_value(); }
    const PinholeCamera& pinhole() const { return *pinhole_; }
    const ProjectiveCamera& projective() const { return *projective_; }
    bool hasLens() const { return projective_ && projective_->hasLens(); }
    // The ray through film position (x, y) in raster units (pixel (i, j)
    // covers [i, i+1) × [j, j+1)), through the lens centre.
    CameraRay centralRay(Vec2f film) const {
        if (pinhole_) return {pinhole_->eye(), pinhole_->direction(film.x, film.y)};
        return projective_->ray(film, {0.5f, 0.5f});
    }

  private:
    std::optional<PinholeCamera> pinhole_;
    std::optional<ProjectiveCamera> projective_;
};

}  // namespace pathlab
