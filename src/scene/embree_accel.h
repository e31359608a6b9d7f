// Ray queries through Embree 3: one RTCScene holding every mesh of a scene as
// triangle geometry (geometry ID = mesh index) and all spheres as one
// sphere-point geometry (geometry ID = mesh count, primitive ID = sphere index).
// Instanced objects (SceneDescription::objects) are each one RTCScene built
// once, laid out the same way (geometry ID = the object's mesh index, its
// spheres after them), and placed by one Embree instance geometry per
// ObjectInstance (top-level geometry ID = instanceGeometryId(instance)).
//
// Queries can be recorded (RayRecorder) so a frame's exact rays can be replayed
// against Embree alone: the limit the renderer's ray throughput is judged by.
#pragma once

#include <embree3/rtcore.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/math.h"
#include "scene/scene.h"
#include "scene/textures/alpha_cutout.h"

namespace pathlab {

// A closest hit, written by a query only where it reports one (no default
// values: a packet's eight would be zeroed on every call for nothing).
struct RayHit {
    float t;
    unsigned geomId, primId;
    float u, v;  // barycentrics of vertices 1 and 2 (triangles)
    // RTC_INVALID_GEOMETRY_ID for top-level geometry; otherwise the top-level
    // geometry ID of the instance hit (EmbreeAccel::instanceIndex), and geomId
    // and primId name the shape inside that instance's object.
    unsigned instId;
};

// A ray as the renderer asked for it: closest hit, or any hit (shadow ray);
// coherent: traced in a packet Embree was told is coherent (a pixel's camera
// rays), which Embree traverses differently — a replay must tell it too.
struct RecordedRay {
    Vec3f o, d;
    float tMax;
    bool shadow;
    bool coherent = false;
};

// Collects every query made while attached to an accelerator, per thread
// without locks; gather() concatenates them once rendering is over.
class RayRecorder {
  public:
    // Out of line and cold: inlined, the copy of o and d into the record made
    // the query functions spill them and reload them across two stores (a
    // store-forwarding stall on every ray, recording or not).
    [[gnu::cold, gnu::noinline]] void record(const Vec3f& o, const Vec3f& d, float tMax,
                                             bool shadow, bool coherent);
    std::vector<RecordedRay> gather() const;

  private:
    tbb::enumerable_thread_specific<std::vector<RecordedRay>> perThread_;
};

// Width of the ray packets: a pixel's camera rays, and the batched paths'
// shadow and bounce rays at one depth.
constexpr int kPacketWidth = 8;

// Up to kPacketWidth rays with their own origins, as structure of arrays (the
// layout of Embree's packets and of the batched shading's output). Each array
// holds kPacketWidth values, all readable; lane k < count is traced where
// active[k] is nonzero, for t in (0, tMax[k]) — (0, ∞) when tMax is null.
struct RayLanes {
    const float *ox, *oy, *oz;
    const float *dx, *dy, *dz;
    const float* tMax;
    const int* active;
    int count;  // lanes 0 … count − 1
};

class EmbreeAccel {
  public:
    // The accelerator may use the meshes' positions and indices in place (see
    // reserveForSharing): `scene` must outlive it unchanged, hence no temporaries.
    explicit EmbreeAccel(const SceneDescription& scene);
    explicit EmbreeAccel(SceneDescription&&) = delete;
    ~EmbreeAccel();
    EmbreeAccel(const EmbreeAccel&) = delete;
    EmbreeAccel& operator=(const EmbreeAccel&) = delete;

    // Closest hit along o + t·d for t in (0, tMax); false on a miss.
    bool intersect(Vec3f o, Vec3f d, float tMax, RayHit* hit) const;
    // Any hit along o + t·d for t in (0, tMax).
    bool occluded(Vec3f o, Vec3f d, float tMax) const;
    // Closest hits of up to kPacketWidth rays from one origin, traced as one
    // Embree packet (rtcIntersect8); found[k] tells whether ray k hit.
    void intersectPacket(Vec3f o, const Vec3f* d, int count, RayHit* hits, bool* found) const;
    // The same for rays of any origins and directions (rtcIntersect8 and
    // rtcOccluded8): found[k] / blocked[k] for the active lanes.
    void intersectLanes(const RayLanes& rays, RayHit* hits, bool* found) const;
    void occludedLanes(const RayLanes& rays, bool* blocked) const;

    // While set (not null), every query is also handed to the recorder.
    void setRecorder(RayRecorder* recorder) { recorder_ = recorder; }
    RTCScene embreeScene() const { return scene_; }

    unsigned sphereGeometryId() const { return sphereGeomId_; }
    // The sphere geometry inside object `object`'s scene (its mesh count), or
    // RTC_INVALID_GEOMETRY_ID when it has no spheres.
    unsigned objectSphereGeometryId(size_t object) const { return objectSphereGeomIds_[object]; }
    // Instance i of SceneDescription::instances is top-level geometry
    // instanceGeometryId(i); a hit's instId maps back with instanceIndex.
    unsigned instanceGeometryId(size_t instance) const {
        return firstInstanceGeomId_ + unsigned(instance);
    }
    size_t instanceIndex(unsigned instId) const { return instId - firstInstanceGeomId_; }
    Vec3f boundsMin() const { return boundsMin_; }
    Vec3f boundsMax() const { return boundsMax_; }
    // Bytes Embree holds for this scene now (BVHs and geometry buffers), as its
    // device's memory monitor reports every allocation and release: what
    // instancing saves is measured here, independent of the process's other
    // allocations.
    size_t embreeBytes() const { return size_t(std::max<int64_t>(embreeBytes_.load(), 0)); }

  private:
    // Traces a filled packet (the hits' IDs are reset here, the rays recorded)
    // and reads back lanes 0 … count − 1.
    void intersect8(RTCRayHit8& rh, const int* valid, int count, RTCIntersectContextFlags flags,
                    RayHit* hits, bool* found) const;

    // The instanced objects' scenes, one per object that some instance places
    // (null for the others), each committed once and shared by its instances.
    void buildObjects(const SceneDescription& desc);
    void attachInstances(const SceneDescription& desc);

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    unsigned sphereGeomId_ = RTC_INVALID_GEOMETRY_ID;
    std::vector<RTCScene> objectScenes_;
    std::vector<unsigned> objectSphereGeomIds_;
    unsigned firstInstanceGeomId_ = 0;
    std::atomic<int64_t> embreeBytes_{0};
    Vec3f boundsMin_, boundsMax_;
    RayRecorder* recorder_ = nullptr;
    // What the filter functions of meshes with an alpha texture read (stable
    // addresses: Embree holds pointers to them).
    std::vector<std::unique_ptr<AlphaCutout>> cutouts_;
};

}  // namespace pathlab
