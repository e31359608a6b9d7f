// Raw Embree throughput on a recorded frame's rays: the limit a renderer built
// on Embree can approach. The same rays are traced with nothing around them —
// one at a time (rtcIntersect1/rtcOccluded1), in packets of 8 (rtcIntersect8/
// rtcOccluded8) and as streams (rtcIntersect1M/rtcOccluded1M) — split into
// chunks over the requested threads. Rays the renderer traced in coherent
// packets (a pixel's camera rays) are replayed with Embree's coherent flag, as
// the renderer traced them: without it Embree traces such a packet as
// incoherent rays, about four times as long (Cornell box camera packets, one
// thread: 25 against 100-odd cycles a ray), and the replay would fall below
// the renderer's own queries instead of bounding them.
#pragma once

#include <string>
#include <vector>

#include "scene/embree_accel.h"

namespace pathlab {

enum class ReplayMode { Single, Packet8, Stream };

std::string replayModeName(ReplayMode mode);

struct ReplayResult {
    double seconds = 0;
    size_t rays = 0;
    size_t hits = 0;     // closest-hit rays that hit plus shadow rays that were blocked
    size_t queries = 0;  // Embree calls: rays, packets or streams
    double raysPerSecond() const { return seconds > 0 ? double(rays) / seconds : 0; }
};

// Traces every ray once; `threads` 0 means all cores. Consecutive rays of the
// same kind (closest hit, coherent closest hit, shadow) form the packets and
// streams, as the renderer produced them. The rays are put in Embree's own
// structures before the clock starts: `seconds` is the time of Embree's calls
// and of the loop that makes them, nothing else.
ReplayResult replayRays(const EmbreeAccel& accel, const std::vector<RecordedRay>& rays,
                        ReplayMode mode, int threads);

}  // namespace pathlab
