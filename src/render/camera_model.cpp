#include "render/camera_model.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "render/sampling_routines.h"

namespace pathlab {

ScreenWindow pbrtScreenWindow(const Camera& c, Vec2i res) {
    const float* w = c.screenWindow;
    if (w[0] != 0 || w[1] != 0 || w[2] != 0 || w[3] != 0) return {w[0], w[1], w[2], w[3]};
    // pbrt-v4's PerspectiveCamera::Create / OrthographicCamera::Create.
    const float frame = c.frameAspectRatio > 0 ? c.frameAspectRatio : float(res.x) / float(res.y);
    if (frame > 1.f) return {-frame, frame, -1.f, 1.f};
    return {-1.f, 1.f, -1.f / frame, 1.f / frame};
}

ProjectiveCamera::ProjectiveCamera(const Camera& c, Vec2i res)
    : perspective_(c.projection == Projection::Perspective),
      eye_(c.eye),
      axisX_(c.axisX),
      axisY_(c.axisY),
      axisZ_(c.axisZ),
      lensRadius_(c.lensRadius),
      focalDistance_(c.focalDistance) {
    const ScreenWindow s = pbrtScreenWindow(c, res);
    if (!(s.xmax != s.xmin && s.ymax != s.ymin) || !std::isfinite(s.xmax - s.xmin) ||
        !std::isfinite(s.ymax - s.ymin))
        throw InputError("camera screen window is empty");
    if (perspective_ && !(c.fov > 0 && c.fov < 180))
        throw InputError("perspective camera fov must be in (0, 180) degrees, got " +
                         std::to_string(c.fov));
    if (!(c.lensRadius >= 0) || (c.lensRadius > 0 && !(c.focalDistance > 0)))
        throw InputError("thin lens needs lensradius >= 0 and focaldistance > 0");
    // rasterFromScreen = Scale(W, −H) · Scale(1/(xmax − xmin), 1/(ymax − ymin))
    // · Translate(−xmin, −ymax): screen x grows with raster x, screen y falls
    // as raster y grows.
    xmin_ = s.xmin;
    ymax_ = s.ymax;
    screenPerPixelX_ = (s.xmax - s.xmin) / float(res.x);
    screenPerPixelY_ = (s.ymax - s.ymin) / float(res.y);
    // pbrt-v4's Perspective(fov) scales x and y by 1/tan(fov/2) into screen space.
    tanHalfFov_ = std::tan(c.fov * kPi / 360.0f);
}

CameraRay ProjectiveCamera::cameraSpaceRay(Vec2f raster, Vec2f uLens) const {
    const Vec2f s = screenFromRaster(raster);
    CameraRay r;
    if (perspective_)
        r = {{0, 0, 0}, normalize(Vec3f(s.x * tanHalfFov_, s.y * tanHalfFov_, 1))};
    else
        r = {{s.x, s.y, 0}, {0, 0, 1}};
    if (lensRadius_ > 0) {
        // The point on the plane of focus that this film position sees
        // sharply, then the ray from the lens point through it.
        const Vec2f d = sampleConcentricDisk(uLens);
        const Vec3f pLens{lensRadius_ * d.x, lensRadius_ * d.y, 0};
        const float ft = focalDistance_ / r.direction.z;
        const Vec3f pFocus = r.origin + r.direction * ft;
        r = {pLens, normalize(pFocus - pLens)};
    }
    return r;
}

}  // namespace pathlab
