#include "scene/embree_accel.h"

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace pathlab {
namespace {

void attachMesh(RTCDevice device, RTCScene scene, const Mesh& mesh) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
        mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        v[3 * i] = mesh.positions[i].x;
        v[3 * i + 1] = mesh.positions[i].y;
        v[3 * i + 2] = mesh.positions[i].z;
    }
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
        mesh.triangleCount()));
    std::memcpy(idx, mesh.indices.data(), mesh.indices.size() * sizeof(unsigned));
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
}

unsigned attachSpheres(RTCDevice device, RTCScene scene, const std::vector<Sphere>& spheres) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
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

}  // namespace

EmbreeAccel::EmbreeAccel(const SceneDescription& desc) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("cannot create the Embree device");
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    for (const Mesh& mesh : desc.meshes) attachMesh(device_, scene_, mesh);
    if (!desc.spheres.empty()) sphereGeomId_ = attachSpheres(device_, scene_, desc.spheres);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
        throw std::runtime_error("Embree failed to build the scene");
    RTCBounds b;
    rtcGetSceneBounds(scene_, &b);
    boundsMin_ = {b.lower_x, b.lower_y, b.lower_z};
    boundsMax_ = {b.upper_x, b.upper_y, b.upper_z};
}

EmbreeAccel::~EmbreeAccel() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
}

bool EmbreeAccel::intersect(Vec3f o, Vec3f d, float tMax, RayHit* hit) const {
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
    hit->ng = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
    return true;
}

bool EmbreeAccel::occluded(Vec3f o, Vec3f d, float tMax) const {
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

}  // namespace pathlab
