#include "view/pass_scheduler.h"

#include <algorithm>
#include <cstdint>

#include "scene/embree_accel.h"

namespace pathlab::view {

PassScheduler::PassScheduler(EqualBy equal, bool hasB, bool progressiveA, bool progressiveB,
                             int maxSpp)
    : equal_(equal), hasB_(hasB), maxSpp_(maxSpp) {
    // At equal spp A and B share A's pace: both continue only if both can.
    const bool together = equal == EqualBy::Spp || !hasB;
    track_[0].progressive = together ? progressiveA && (!hasB || progressiveB) : progressiveA;
    track_[1].progressive = progressiveB;
}

bool PassScheduler::done() const {
    return track_[0].spp >= maxSpp_ && (!hasB_ || track_[1].spp >= maxSpp_);
}

// How long a progressive sampler's passes may grow after `seconds` of
// rendering: a quarter second at first (the image changes fast), then a
// fifth of the time so far, up to kLongestPass. Each pass costs a fixed part
// besides its samples — each pixel's sampler set-up and path batches that
// pass's few samples leave part-empty (render/path_integrator.h): ≈ 80 ms at
// 512² on two cores, a pass of 8 spp costing as much as 10 — so short passes
// would keep that share high (×1.24 the render's time at 1024 spp with the
// 8-spp passes of a fixed quarter second); growing with the elapsed time
// brings it to ≈ 4% there, while the image still updates at least every
// 2 × kLongestPass (tests/test_view_equal_time.cpp models it).
double PassScheduler::passSecondsAfter(double seconds) {
    return std::clamp(0.2 * seconds, 0.25, kLongestPass);
}

// The sample count of a sampler's next pass. The first pass is 1 spp, so a
// restart shows an image at once. Progressive samplers then add a batch that
// doubles up to kPacketWidth samples, and beyond while passes take under
// passSecondsAfter (the render time so far), and halves when one takes over
// twice that, but never below kPacketWidth: a pixel's samples are traced as
// packets of eight and their paths in batches (render/path_integrator.h),
// and passes of one sample would leave the packets nearly empty — at 512²
// sixteen 1-spp passes took 1.9 times as long as one 16-spp render
// (bench/view_interactivity.py). Other samplers render each pass afresh:
// doubling the count keeps the total within twice the last pass.
int PassScheduler::nextCount(Track& t, double lastPassSeconds) const {
    if (t.spp == 0) return 1;
    if (!t.progressive) return std::min(maxSpp_, t.spp * 2);
    const double longest = passSecondsAfter(t.seconds);
    if ((t.batch < kPacketWidth || lastPassSeconds < longest) && t.batch < (1 << 20)) t.batch *= 2;
    if (lastPassSeconds > 2 * longest && t.batch > kPacketWidth) t.batch /= 2;
    return int(std::min<int64_t>(maxSpp_, int64_t(t.spp) + t.batch));
}

Pass PassScheduler::next() {
    Pass pass;
    if (equal_ == EqualBy::Spp || !hasB_) {
        // Both together, at the pace of the pair: a pass is A's and B's.
        Track& a = track_[0];
        const int target = nextCount(a, a.lastPass + (hasB_ ? track_[1].lastPass : 0));
        pass.target = {target, hasB_ ? target : 0};
        return pass;
    }
    // Equal time: the sampler behind in render time goes next (A on a tie),
    // unless it has reached the end.
    const bool aDone = track_[0].spp >= maxSpp_, bDone = track_[1].spp >= maxSpp_;
    const int which = aDone || (!bDone && track_[1].seconds < track_[0].seconds) ? 1 : 0;
    Track& t = track_[which];
    pass.target[which] = nextCount(t, t.lastPass);
    return pass;
}

void PassScheduler::finished(const Pass& pass, double secondsA, double secondsB) {
    const double seconds[2] = {secondsA, secondsB};
    for (int i = 0; i < 2; ++i) {
        if (pass.target[i] == 0) continue;
        track_[i].spp = pass.target[i];
        track_[i].lastPass = seconds[i];
        track_[i].seconds += seconds[i];
    }
}

}  // namespace pathlab::view
