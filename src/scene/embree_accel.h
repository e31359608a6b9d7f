// Ray queries through Embree 3: one RTCScene holding every mesh of a scene as
// triangle geometry (geometry ID = mesh index) and all spheres as one
// sphere-point geometry (geometry ID = mesh count, primitive ID = sphere index).
#pragma once

#include <embree3/rtcore.h>

#include <vector>

#include "core/math.h"
#include "scene/scene.h"

namespace pathlab {

struct RayHit {
    float t = 0;
    unsigned geomId = RTC_INVALID_GEOMETRY_ID;
    unsigned primId = 0;
    float u = 0, v = 0;  // barycentrics of vertices 1 and 2 (triangles)
    Vec3f ng;            // Embree's unnormalised geometric normal (used for spheres)
};

class EmbreeAccel {
public:
    explicit EmbreeAccel(const SceneDescription& scene);
    ~EmbreeAccel();
    EmbreeAccel(const EmbreeAccel&) = delete;
    EmbreeAccel& operator=(const EmbreeAccel&) = delete;

    // Closest hit along o + t·d for t in (0, tMax); false on a miss.
    bool intersect(Vec3f o, Vec3f d, float tMax, RayHit* hit) const;
    // Any hit along o + t·d for t in (0, tMax).
    bool occluded(Vec3f o, Vec3f d, float tMax) const;

    unsigned sphereGeometryId() const { return sphereGeomId_; }
    Vec3f boundsMin() const { return boundsMin_; }
    Vec3f boundsMax() const { return boundsMax_; }

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    unsigned sphereGeomId_ = RTC_INVALID_GEOMETRY_ID;
    Vec3f boundsMin_, boundsMax_;
};

}  // namespace pathlab
