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

// Queries per task: enough that scheduling costs nothing next to tracing.
constexpr size_t kRaysPerTask = 4096;
constexpr size_t kPacketsPerTask = 512;
constexpr size_t kStreamsPerTask = 64;
constexpr unsigned kStreamLength = 64;

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

// Embree's context for a query of rays of this kind.
RTCIntersectContext contextFor(bool coherent) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags =
        coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    return context;
}

RTCRay embreeRay(const RecordedRay& r) {
    RTCRay ray;
    ray.org_x = r.o.x, ray.org_y = r.o.y, ray.org_z = r.o.z;
    ray.dir_x = r.d.x, ray.dir_y = r.d.y, ray.dir_z = r.d.z;
    ray.tnear = 0;
    ray.tfar = r.tMax;
    ray.time = 0;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    return ray;
}

void resetHit(RTCHit& hit) {
    hit.geomID = RTC_INVALID_GEOMETRY_ID;
    hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

struct Traced {
    size_t hits = 0, queries = 0;
};

// The rays in Embree's own structures, built before the clock starts and
// traced where they lie: the timed loops only call Embree and count its
// answers, so the rate is Embree's alone. (Converting the recorded rays on
// the fly took an eighth of the packet replay's time, timed around the calls;
// copying ready packets to the stack, a rep movsq, was slower still: one
// thread, Cornell box, 28.6 and 27.2 against 31.5 M rays/s in place.)
// Embree overwrites tfar and the hits, so each replay prepares its own.
struct PreparedRays {
    // Single rays and streams: every ray, and the runs of one kind (up to
    // kStreamLength rays each) the streams trace.
    std::vector<RTCRayHit> rays;
    std::vector<char> shadow;
    struct Run {
        size_t first;
        unsigned count;
        bool shadow, coherent;
    };
    std::vector<Run> runs;
    // Packets: up to 8 consecutive rays of one kind each.
    struct Packet {
        RTCRayHit8 rays;
        alignas(32) int valid[8];
        int count;
        bool shadow, coherent;
    };
    std::vector<Packet> packets;
};

template <typename Ray8>
void setLane(Ray8& packet, int k, const RTCRay& r) {
    packet.org_x[k] = r.org_x, packet.org_y[k] = r.org_y, packet.org_z[k] = r.org_z;
    packet.dir_x[k] = r.dir_x, packet.dir_y[k] = r.dir_y, packet.dir_z[k] = r.dir_z;
    packet.tnear[k] = r.tnear, packet.tfar[k] = r.tfar, packet.time[k] = r.time;
    packet.mask[k] = r.mask, packet.id[k] = unsigned(k), packet.flags[k] = r.flags;
}

void addPacket(PreparedRays& p, const RecordedRay* first, size_t count) {
    PreparedRays::Packet& packet = p.packets.emplace_back();
    for (int k = 0; k < 8; ++k) {
        // Lanes past count repeat the last ray, masked off.
        setLane(packet.rays.ray, k, embreeRay(first[std::min(size_t(k), count - 1)]));
        packet.rays.hit.geomID[k] = packet.rays.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        packet.valid[k] = size_t(k) < count ? -1 : 0;
    }
    packet.count = int(count), packet.shadow = first->shadow, packet.coherent = first->coherent;
}

PreparedRays prepare(const std::vector<RecordedRay>& recorded, ReplayMode mode) {
    PreparedRays p;
    if (mode != ReplayMode::Packet8) {
        p.rays.resize(recorded.size());
        for (size_t i = 0; i < recorded.size(); ++i) {
            p.rays[i].ray = embreeRay(recorded[i]);
            resetHit(p.rays[i].hit);
            p.shadow.push_back(recorded[i].shadow);
        }
    }
    if (mode == ReplayMode::Single) return p;
    const size_t limit = mode == ReplayMode::Packet8 ? 8 : kStreamLength;
    for (size_t i = 0; i < recorded.size();) {
        const size_t count = runOfOneKind(recorded.data() + i, recorded.size() - i, limit);
        if (mode == ReplayMode::Stream)
            p.runs.push_back({i, unsigned(count), recorded[i].shadow, recorded[i].coherent});
        else
            addPacket(p, recorded.data() + i, count);
        i += count;
    }
    return p;
}

Traced traceSingle(RTCScene scene, PreparedRays& p, size_t begin, size_t end) {
    RTCIntersectContext context = contextFor(false);
    Traced traced;
    for (size_t i = begin; i < end; ++i) {
        RTCRayHit& rh = p.rays[i];
        if (p.shadow[i]) {
            rtcOccluded1(scene, &context, &rh.ray);
            traced.hits += rh.ray.tfar < 0;
        } else {
            rtcIntersect1(scene, &context, &rh);
            traced.hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
    }
    traced.queries = end - begin;
    return traced;
}

Traced tracePackets(RTCScene scene, PreparedRays& p, size_t begin, size_t end) {
    Traced traced;
    for (size_t i = begin; i < end; ++i) {
        PreparedRays::Packet& packet = p.packets[i];
        RTCIntersectContext context = contextFor(packet.coherent);
        RTCRayHit8& rh = packet.rays;
        if (packet.shadow) {
            rtcOccluded8(packet.valid, scene, &context, &rh.ray);
            for (int k = 0; k < packet.count; ++k) traced.hits += rh.ray.tfar[k] < 0;
        } else {
            rtcIntersect8(packet.valid, scene, &context, &rh);
            for (int k = 0; k < packet.count; ++k)
                traced.hits += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        }
    }
    traced.queries = end - begin;
    return traced;
}

Traced traceStreams(RTCScene scene, PreparedRays& p, size_t begin, size_t end) {
    Traced traced;
    for (size_t i = begin; i < end; ++i) {
        const PreparedRays::Run& run = p.runs[i];
        RTCIntersectContext context = contextFor(run.coherent);
        RTCRayHit* stream = p.rays.data() + run.first;
        if (run.shadow) {
            rtcOccluded1M(scene, &context, &stream->ray, run.count, sizeof(RTCRayHit));
            for (unsigned k = 0; k < run.count; ++k) traced.hits += stream[k].ray.tfar < 0;
        } else {
            rtcIntersect1M(scene, &context, stream, run.count, sizeof(RTCRayHit));
            for (unsigned k = 0; k < run.count; ++k)
                traced.hits += stream[k].hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
    }
    traced.queries = end - begin;
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
    ReplayResult result;
    result.rays = rays.size();
    if (rays.empty()) return result;
    std::optional<tbb::global_control> limit;
    if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
    const RTCScene scene = accel.embreeScene();
    PreparedRays prepared = prepare(rays, mode);
    const size_t queries = mode == ReplayMode::Single    ? prepared.rays.size()
                           : mode == ReplayMode::Packet8 ? prepared.packets.size()
                                                         : prepared.runs.size();
    const size_t perTask = mode == ReplayMode::Single    ? kRaysPerTask
                           : mode == ReplayMode::Packet8 ? kPacketsPerTask
                                                         : kStreamsPerTask;
    tbb::enumerable_thread_specific<Traced> traced;
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(size_t(0), (queries + perTask - 1) / perTask, [&](size_t task) {
        const ScopedFlushDenormals denormals;  // as the renderer traces them
        const size_t begin = task * perTask, end = std::min(queries, begin + perTask);
        const Traced t = mode == ReplayMode::Single    ? traceSingle(scene, prepared, begin, end)
                         : mode == ReplayMode::Packet8 ? tracePackets(scene, prepared, begin, end)
                                                       : traceStreams(scene, prepared, begin, end);
        traced.local().hits += t.hits, traced.local().queries += t.queries;
    });
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const Traced& t : traced) result.hits += t.hits, result.queries += t.queries;
    return result;
}

}  // namespace pathlab
