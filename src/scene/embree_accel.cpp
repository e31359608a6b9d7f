#include "scene/embree_accel.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace pathlab {
namespace {

// Up to this many geometries the scene is a two-level structure: a top node
// over the meshes' own trees. The Cornell box's seven objects and its light
// are then one BVH8 node whose children are the objects, and its rays cost
// about 25% less than in one SAH tree over all triangles (raw replay, one
// thread: 12.2 → 16.0 M rays/s; the wolf, three meshes, is unchanged). With
// many meshes the objects' boxes overlap and one tree over all triangles
// traces faster, so larger scenes keep it.
constexpr size_t kMaxTwoLevelGeometries = 16;

// Embree reads a buffer's last element with a 16-byte load, so a buffer it
// shares must hold 4 readable bytes past the data: a vector whose capacity
// exceeds its size does (Mesh::reserveForSharing).
template <typename T>
bool shareable(const std::vector<T>& v) {
    return (v.capacity() - v.size()) * sizeof(T) >= 4;
}

// The mesh's positions and indices go to Embree as they are when it can share
// them (no copy: 24 bytes per triangle of a typical mesh), else copied.
// A mesh with an alpha texture gets filter functions reading `cutout`.
void attachMesh(RTCDevice device, RTCScene scene, const Mesh& mesh, const AlphaCutout* cutout) {
    static_assert(sizeof(Vec3f) == 3 * sizeof(float));
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
    const size_t vertices = mesh.positions.size(), triangles = mesh.triangleCount();
    if (shareable(mesh.positions)) {
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                   mesh.positions.data(), 0, sizeof(Vec3f), vertices);
    } else {
        void* v = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                          sizeof(Vec3f), vertices);
        std::memcpy(v, mesh.positions.data(), vertices * sizeof(Vec3f));
    }
    if (shareable(mesh.indices)) {
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                   mesh.indices.data(), 0, 3 * sizeof(unsigned), triangles);
    } else {
        void* idx = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                            3 * sizeof(unsigned), triangles);
        std::memcpy(idx, mesh.indices.data(), mesh.indices.size() * sizeof(unsigned));
    }
    if (cutout) attachAlphaFilter(geom, cutout);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
}

unsigned attachSpheres(RTCDevice device, RTCScene scene, const std::vector<Sphere>& spheres) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), spheres.size()));
    for (size_t i = 0; i < spheres.size(); ++i) {
        v[4 * i] = spheres[i].center.x;
        v[4 * i + 1] = spheres[i].center.y;
        v[4 * i + 2] = spheres[i].center.z;
        v[4 * i + 3] = spheres[i].radius;
    }
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    return id;
}

// Embree's memory monitor: every allocation (positive) and release (negative)
// the device makes, summed into the accelerator's count. Embree calls it from
// its build threads; the release half pairs with the destructor's acquire.
bool countEmbreeBytes(void* counter, ssize_t bytes, bool /*post*/) {
    static_cast<std::atomic<int64_t>*>(counter)->fetch_add(int64_t(bytes),
                                                           std::memory_order_acq_rel);
    return true;
}

// Meshes (geometry ID = index) and then spheres (one geometry) into `scene`,
// committed; returns the spheres' geometry ID, or RTC_INVALID_GEOMETRY_ID.
unsigned buildShapes(RTCDevice device, RTCScene scene, const std::vector<Mesh>& meshes,
                     const std::vector<Sphere>& spheres, const SceneDescription& desc,
                     std::vector<std::unique_ptr<AlphaCutout>>& cutouts) {
    // Scene quality LOW asks Embree for its two-level structure, in which each
    // geometry keeps the build quality set on it (HIGH: spatial-split SAH).
    const size_t geometries = meshes.size() + (spheres.empty() ? 0 : 1);
    rtcSetSceneBuildQuality(scene, geometries <= kMaxTwoLevelGeometries ? RTC_BUILD_QUALITY_LOW
                                                                        : RTC_BUILD_QUALITY_HIGH);
    for (const Mesh& mesh : meshes) {
        const AlphaCutout* cutout = nullptr;
        if (mesh.alphaTexture >= 0) {
            cutouts.push_back(std::make_unique<AlphaCutout>(AlphaCutout{&mesh, &desc}));
            cutout = cutouts.back().get();
        }
        attachMesh(device, scene, mesh, cutout);
    }
    return spheres.empty() ? RTC_INVALID_GEOMETRY_ID : attachSpheres(device, scene, spheres);
}

}  // namespace

EmbreeAccel::EmbreeAccel(const SceneDescription& desc) {
    // validateScene rejects this; checked here too (before anything is
    // allocated) for scenes built in code and never validated.
    for (const ObjectInstance& inst : desc.instances)
        if (inst.object < 0 || size_t(inst.object) >= desc.objects.size())
            throw std::runtime_error("an instance refers to object " + std::to_string(inst.object) +
                                     ", which does not exist");
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("cannot create the Embree device");
    rtcSetDeviceMemoryMonitorFunction(device_, countEmbreeBytes, &embreeBytes_);
    buildObjects(desc);
    scene_ = rtcNewScene(device_);
    sphereGeomId_ = buildShapes(device_, scene_, desc.meshes, desc.spheres, desc, cutouts_);
    attachInstances(desc);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
        throw std::runtime_error("Embree failed to build the scene");
    RTCBounds b;
    rtcGetSceneBounds(scene_, &b);
    boundsMin_ = {b.lower_x, b.lower_y, b.lower_z};
    boundsMax_ = {b.upper_x, b.upper_y, b.upper_z};
}

void EmbreeAccel::buildObjects(const SceneDescription& desc) {
    objectScenes_.assign(desc.objects.size(), nullptr);
    objectSphereGeomIds_.assign(desc.objects.size(), RTC_INVALID_GEOMETRY_ID);
    // Only placed objects are built: an unused ObjectBegin costs nothing.
    std::vector<char> used(desc.objects.size(), 0);
    for (const ObjectInstance& inst : desc.instances) used[size_t(inst.object)] = 1;
    for (size_t i = 0; i < desc.objects.size(); ++i) {
        const InstancedObject& object = desc.objects[i];
        if (!used[i] || (object.meshes.empty() && object.spheres.empty())) continue;
        objectScenes_[i] = rtcNewScene(device_);
        objectSphereGeomIds_[i] =
            buildShapes(device_, objectScenes_[i], object.meshes, object.spheres, desc, cutouts_);
        rtcCommitScene(objectScenes_[i]);
    }
}

void EmbreeAccel::attachInstances(const SceneDescription& desc) {
    // Instance i gets top-level ID first + i, after every mesh and the spheres,
    // so that meshes keep geometry ID = mesh index. IDs of instances of empty
    // objects (nothing attached) are simply left unused.
    firstInstanceGeomId_ = unsigned(desc.meshes.size() + (desc.spheres.empty() ? 0 : 1));
    for (size_t i = 0; i < desc.instances.size(); ++i) {
        const ObjectInstance& inst = desc.instances[i];
        RTCScene object = objectScenes_[size_t(inst.object)];
        if (!object) continue;
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geom, object);
        // Column-major 3×4: the columns of M, then the translation.
        const Affine& xf = inst.objectToWorld;
        float m[12];
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) m[3 * c + r] = xf.m[r][c];
        m[9] = xf.t.x, m[10] = xf.t.y, m[11] = xf.t.z;
        rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, m);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(scene_, geom, instanceGeometryId(i));
        rtcReleaseGeometry(geom);
    }
}

EmbreeAccel::~EmbreeAccel() {
    if (scene_) rtcReleaseScene(scene_);
    for (RTCScene object : objectScenes_)
        if (object) rtcReleaseScene(object);
    if (device_) rtcReleaseDevice(device_);
    // The last count written by an Embree worker happens before the counter is
    // freed: the build joined inside libembree/libtbb, which ThreadSanitizer
    // cannot see, so the acquire load states the order in code it does see.
    (void)embreeBytes_.load(std::memory_order_acquire);
}

void RayRecorder::record(const Vec3f& o, const Vec3f& d, float tMax, bool shadow, bool coherent) {
    perThread_.local().push_back({o, d, tMax, shadow, coherent});
}

std::vector<RecordedRay> RayRecorder::gather() const {
    std::vector<RecordedRay> all;
    for (const auto& rays : perThread_) all.insert(all.end(), rays.begin(), rays.end());
    return all;
}

bool EmbreeAccel::intersect(Vec3f o, Vec3f d, float tMax, RayHit* hit) const {
    if (recorder_) recorder_->record(o, d, tMax, false, false);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
    rh.ray.tnear = 0;
    rh.ray.tfar = tMax;
    rh.ray.time = 0;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit->t = rh.ray.tfar;
    hit->geomId = rh.hit.geomID;
    hit->primId = rh.hit.primID;
    hit->u = rh.hit.u;
    hit->v = rh.hit.v;
    hit->instId = rh.hit.instID[0];
    return true;
}

bool EmbreeAccel::occluded(Vec3f o, Vec3f d, float tMax) const {
    if (recorder_) recorder_->record(o, d, tMax, true, false);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    ray.org_x = o.x, ray.org_y = o.y, ray.org_z = o.z;
    ray.dir_x = d.x, ray.dir_y = d.y, ray.dir_z = d.z;
    ray.tnear = 0;
    ray.tfar = tMax;
    ray.time = 0;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(scene_, &context, &ray);
    // Embree sets tfar to −inf when the ray is blocked.
    return ray.tfar < 0;
}

namespace {

// The fields every packet lane gets whatever its ray: no near distance, time
// 0, every geometry, its lane as ID.
template <typename Ray8>
void setLaneDefaults(Ray8& ray) {
    for (int k = 0; k < kPacketWidth; ++k) {
        ray.tnear[k] = 0;
        ray.time[k] = 0;
        ray.mask[k] = 0xFFFFFFFFu;
        ray.id[k] = unsigned(k);
        ray.flags[k] = 0;
    }
}

// Lanes of `rays` into an Embree packet (RTCRay8, or RTCRayHit8's ray); the
// valid mask marks the active ones. Whole arrays are copied, inactive lanes
// too (Embree ignores them): eight-float moves, no branch per lane.
template <typename Ray8>
void setPacketLanes(const RayLanes& rays, Ray8& ray, int* valid) {
    constexpr size_t kBytes = sizeof(float) * kPacketWidth;
    std::memcpy(ray.org_x, rays.ox, kBytes), std::memcpy(ray.org_y, rays.oy, kBytes);
    std::memcpy(ray.org_z, rays.oz, kBytes), std::memcpy(ray.dir_x, rays.dx, kBytes);
    std::memcpy(ray.dir_y, rays.dy, kBytes), std::memcpy(ray.dir_z, rays.dz, kBytes);
    if (rays.tMax)
        std::memcpy(ray.tfar, rays.tMax, kBytes);
    else
        std::fill_n(ray.tfar, kPacketWidth, std::numeric_limits<float>::infinity());
    for (int k = 0; k < kPacketWidth; ++k)
        valid[k] = -int(k < rays.count) & -int(rays.active[k] != 0);
    setLaneDefaults(ray);
}

// A packet's active lanes to the recorder, if there is one.
template <typename Ray8>
void recordLanes(RayRecorder* recorder, const Ray8& ray, const int* valid, bool shadow,
                 bool coherent) {
    if (!recorder) return;
    for (int k = 0; k < kPacketWidth; ++k)
        if (valid[k])
            recorder->record({ray.org_x[k], ray.org_y[k], ray.org_z[k]},
                             {ray.dir_x[k], ray.dir_y[k], ray.dir_z[k]}, ray.tfar[k], shadow,
                             coherent);
}

}  // namespace

void EmbreeAccel::intersectPacket(Vec3f o, const Vec3f* d, int count, RayHit* hits,
                                  bool* found) const {
    if (count == 1) {
        found[0] = intersect(o, d[0], std::numeric_limits<float>::infinity(), &hits[0]);
        return;
    }
    alignas(32) int valid[kPacketWidth];
    alignas(32) RTCRayHit8 rh;
    for (int k = 0; k < kPacketWidth; ++k) {
        const bool active = k < count;
        valid[k] = active ? -1 : 0;
        const Vec3f dir = active ? d[k] : Vec3f(0, 0, 1);
        rh.ray.org_x[k] = o.x, rh.ray.org_y[k] = o.y, rh.ray.org_z[k] = o.z;
        rh.ray.dir_x[k] = dir.x, rh.ray.dir_y[k] = dir.y, rh.ray.dir_z[k] = dir.z;
        rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
    }
    setLaneDefaults(rh.ray);
    intersect8(rh, valid, count, RTC_INTERSECT_CONTEXT_FLAG_COHERENT, hits, found);
}

void EmbreeAccel::intersect8(RTCRayHit8& rh, const int* valid, int count,
                             RTCIntersectContextFlags flags, RayHit* hits, bool* found) const {
    for (int k = 0; k < kPacketWidth; ++k) {
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    recordLanes(recorder_, rh.ray, valid, false, flags == RTC_INTERSECT_CONTEXT_FLAG_COHERENT);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = flags;
    rtcIntersect8(valid, scene_, &context, &rh);
    for (int k = 0; k < count; ++k) {
        found[k] = valid[k] && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        if (!found[k]) continue;
        RayHit& hit = hits[k];
        hit.t = rh.ray.tfar[k];
        hit.geomId = rh.hit.geomID[k];
        hit.primId = rh.hit.primID[k];
        hit.u = rh.hit.u[k];
        hit.v = rh.hit.v[k];
        hit.instId = rh.hit.instID[0][k];
    }
}

void EmbreeAccel::intersectLanes(const RayLanes& rays, RayHit* hits, bool* found) const {
    alignas(32) int valid[kPacketWidth];
    alignas(32) RTCRayHit8 rh;
    setPacketLanes(rays, rh.ray, valid);
    intersect8(rh, valid, rays.count, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT, hits, found);
}

void EmbreeAccel::occludedLanes(const RayLanes& rays, bool* blocked) const {
    alignas(32) int valid[kPacketWidth];
    alignas(32) RTCRay8 ray;
    setPacketLanes(rays, ray, valid);
    recordLanes(recorder_, ray, valid, true, false);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded8(valid, scene_, &context, &ray);
    // Embree sets tfar to −inf where a ray is blocked.
    for (int k = 0; k < rays.count; ++k) blocked[k] = valid[k] && ray.tfar[k] < 0;
}

}  // namespace pathlab
