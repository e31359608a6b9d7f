// A pinhole camera. Image x runs to the right, y downwards (row 0 is the top).
// Image right is normalize(cross(forward, up)): with forward +z and up +y that
// is −x, so the Cornell box's red wall (x ≈ 550) appears on the left as in the
// classic photograph. (pbrt-v4 scenes' cameras, with their lens and
// orthographic projection: camera_model.h.)
#pragma once

#include <cmath>

#include "core/math.h"
#include "scene/scene.h"

namespace pathlab {

class PinholeCamera {
  public:
    PinholeCamera(const Camera& c, Vec2i resolution) : eye_(c.eye) {
        const Vec3f forward = normalize(c.target - c.eye);
        const Vec3f right = normalize(cross(forward, c.up));
        const Vec3f up = cross(right, forward);
        const float tanHalf = std::tan(c.fovY * kPi / 360.0f);
        const float aspect = float(resolution.x) / float(resolution.y);
        // Direction through film position (fx, fy) in pixels:
        // forward + right·(2fx/W − 1)·tan·aspect + up·(1 − 2fy/H)·tan.
        origin_ = forward - right * (tanHalf * aspect) + up * tanHalf;
        dx_ = right * (2 * tanHalf * aspect / float(resolution.x));
        dy_ = up * (-2 * tanHalf / float(resolution.y));
    }
    Vec3f eye() const { return eye_; }
    // Unit direction through the film position (x, y), in pixel units.
    Vec3f direction(float x, float y) const { return normalize(origin_ + dx_ * x + dy_ * y); }

  private:
    Vec3f eye_, origin_, dx_, dy_;
};

}  // namespace pathlab
