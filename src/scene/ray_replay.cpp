#include "scene/ray_replay.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <optional>

#include "core/float_mode.h"

namespace pathlab {
namespace {

// Rays per task: large enough that scheduling costs nothing next to tracing.
constexpr size_t kChunk = 4096;
constexpr size_t kStreamLength = 64;

void setRay(RTCRay& ray, const RecordedRay& r) {
    ray.org_x = r.o.x, ray.org_y = r.o.y, ray.org_z = r.o.z;
    ray.dir_x = r.d.x, ray.dir_y = r.d.y, ray.dir_z = r.d.z;
    ray.tnear = 0;
    ray.tfar = r.tMax;
    ray.time = 0;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
}

// Whether two rays are traced by the same kind of query.
bool sameKind(const RecordedRay& a, const RecordedRay& b) {
    return a.shadow == b.shadow && a.coherent == b.coherent;
}

// How many of the (up to `limit`) rays from `first` on are of its kind.
size_t runOfOneKind(const RecordedRay* first, size_t n, size_t limit) {
    size_t count = 1;
    while (count < limit && count < n && sameKind(first[count], first[0])) ++count;
    return count;
}

// Embree's context for a group of rays of first's kind.
RTCIntersectContext contextFor(const RecordedRay& first) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = first.coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                   : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    return context;
}

struct Traced {
    size_t hits = 0, queries = 0;
};

Traced traceSingle(RTCScene scene, const RecordedRay* rays, size_t n) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    Traced traced;
    for (size_t i = 0; i < n; ++i) {
        if (rays[i].shadow) {
            RTCRay ray;
            setRay(ray, rays[i]);
            rtcOccluded1(scene, &context, &ray);
            traced.hits += ray.tfar < 0;
        } else {
            RTCRayHit rh;
            setRay(rh.ray, rays[i]);
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &context, &rh);
            traced.hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
    }
    traced.queries = n;
    return traced;
}

// Writes ray i of a packet (SOA layout shared by RTCRay8 and RTCRayHit8.ray).
template <typename Ray8>
void setLane(Ray8& ray, int k, const RecordedRay& r) {
    ray.org_x[k] = r.o.x, ray.org_y[k] = r.o.y, ray.org_z[k] = r.o.z;
    ray.dir_x[k] = r.d.x, ray.dir_y[k] = r.d.y, ray.dir_z[k] = r.d.z;
    ray.tnear[k] = 0;
    ray.tfar[k] = r.tMax;
    ray.time[k] = 0;
    ray.mask[k] = 0xFFFFFFFFu;
    ray.id[k] = unsigned(k);
    ray.flags[k] = 0;
}

Traced tracePackets(RTCScene scene, const RecordedRay* rays, size_t n) {
    Traced traced;
    for (size_t i = 0; i < n; ++traced.queries) {
        // A packet: up to 8 consecutive rays of the same kind.
        const int count = int(runOfOneKind(rays + i, n - i, 8));
        RTCIntersectContext context = contextFor(rays[i]);
        alignas(32) int valid[8];
        for (int k = 0; k < 8; ++k) valid[k] = k < count ? -1 : 0;
        if (rays[i].shadow) {
            alignas(32) RTCRay8 ray;
            for (int k = 0; k < count; ++k) setLane(ray, k, rays[i + size_t(k)]);
            rtcOccluded8(valid, scene, &context, &ray);
            for (int k = 0; k < count; ++k) traced.hits += ray.tfar[k] < 0;
        } else {
            alignas(32) RTCRayHit8 rh;
            for (int k = 0; k < count; ++k) {
                setLane(rh.ray, k, rays[i + size_t(k)]);
                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect8(valid, scene, &context, &rh);
            for (int k = 0; k < count; ++k)
                traced.hits += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        }
        i += size_t(count);
    }
    return traced;
}

Traced traceStreams(RTCScene scene, const RecordedRay* rays, size_t n) {
    RTCRayHit hitRays[kStreamLength];
    RTCRay shadowRays[kStreamLength];
    Traced traced;
    for (size_t i = 0; i < n; ++traced.queries) {
        const unsigned count = unsigned(runOfOneKind(rays + i, n - i, kStreamLength));
        RTCIntersectContext context = contextFor(rays[i]);
        if (rays[i].shadow) {
            for (unsigned k = 0; k < count; ++k) setRay(shadowRays[k], rays[i + k]);
            rtcOccluded1M(scene, &context, shadowRays, count, sizeof(RTCRay));
            for (unsigned k = 0; k < count; ++k) traced.hits += shadowRays[k].tfar < 0;
        } else {
            for (unsigned k = 0; k < count; ++k) {
                setRay(hitRays[k].ray, rays[i + k]);
                hitRays[k].hit.geomID = RTC_INVALID_GEOMETRY_ID;
                hitRays[k].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect1M(scene, &context, hitRays, count, sizeof(RTCRayHit));
            for (unsigned k = 0; k < count; ++k)
                traced.hits += hitRays[k].hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        i += count;
    }
    return traced;
}

}  // namespace

std::string replayModeName(ReplayMode mode) {
    switch (mode) {
        case ReplayMode::Single:
            return "single";
        case ReplayMode::Packet8:
            return "packet8";
        case ReplayMode::Stream:
            return "stream";
    }
    return "single";
}

ReplayResult replayRays(const EmbreeAccel& accel, const std::vector<RecordedRay>& rays,
                        ReplayMode mode, int threads) {
    std::optional<tbb::global_control> limit;
    if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
    const RTCScene scene = accel.embreeScene();
    tbb::enumerable_thread_specific<Traced> traced;
    const size_t chunks = (rays.size() + kChunk - 1) / kChunk;
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
        const ScopedFlushDenormals denormals;  // as the renderer traces them
        const size_t begin = c * kChunk, n = std::min(kChunk, rays.size() - begin);
        const RecordedRay* first = rays.data() + begin;
        const Traced t = mode == ReplayMode::Single    ? traceSingle(scene, first, n)
                         : mode == ReplayMode::Packet8 ? tracePackets(scene, first, n)
                                                       : traceStreams(scene, first, n);
        traced.local().hits += t.hits, traced.local().queries += t.queries;
    });
    ReplayResult result;
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.rays = rays.size();
    for (const Traced& t : traced) result.hits += t.hits, result.queries += t.queries;
    return result;
}

}  // namespace pathlab
