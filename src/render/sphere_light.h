// Sampling an emitting sphere for next-event estimation, as pbrt-v4's
// Sphere::Sample(ctx, u) and Sphere::PDF (PBRT 4th ed., §6.2.4): from a
// receiver outside the sphere, a direction uniform in the cone of directions
// the sphere subtends, and the point where it first meets the sphere; from a
// receiver inside (or on) it, where there is no such cone, a point uniform
// over its area. Uniform area sampling from outside is kept for comparison
// (half its points lie on the far side, hidden by the sphere itself).
#pragma once

#include <optional>

#include "core/math.h"

namespace pathlab {

// A point on the sphere and its density per unit solid angle at the receiver.
struct SpherePoint {
    Vec3f p;
    float pdf;
};

// Whether the cone exists: the receiver is outside the sphere by more than a
// relative 10⁻⁴ of r² in squared distance. A receiver on the sphere itself
// (an emitter's own diffuse surface) would see a hemisphere-wide cone whose
// apex touches the sphere; pbrt-v4 likewise treats it as inside, by moving
// the reference point towards the centre by its error bound.
bool sphereConeExists(Vec3f center, float radius, Vec3f ref);

// Uniform in the subtended cone: density 1 / (2π (1 − cos θmax)).
SpherePoint sampleSphereCone(Vec3f center, float radius, Vec3f ref, Vec2f u);
float sphereConePdf(Vec3f center, float radius, Vec3f ref);

// Uniform over the area 4πr², converted to solid angle at ref:
// dist² / (4πr² |cos θ'|), θ' the angle at p between the normal and ref − p.
// Nothing (or density 0) when p coincides with ref or is seen edge-on.
std::optional<SpherePoint> sampleSphereArea(Vec3f center, float radius, Vec3f ref, Vec2f u);
float sphereAreaPdf(Vec3f center, float radius, Vec3f ref, Vec3f p);

}  // namespace pathlab
