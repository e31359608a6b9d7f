// Which sampler `pathlab view` renders next, and to what sample count. At
// equal spp every pass brings A and B to the same count; at equal time each
// pass advances whichever of the two has had less render time so far, so
// both get the same wall-clock share and the cheaper sampler reaches a higher
// spp — the comparison a user of a renderer with a time budget cares about.
#pragma once

#include <array>

namespace pathlab::view {

enum class EqualBy { Spp, Time };

// The sample counts a pass brings A and B to; 0: that sampler is not
// rendered in this pass.
struct Pass {
    std::array<int, 2> target{0, 0};
};

class PassScheduler {
  public:
    PassScheduler(EqualBy equal, bool hasB, bool progressiveA, bool progressiveB, int maxSpp);

    bool done() const;  // every sampler at maxSpp
    // The next pass (call only when !done()); it adapts the batch size.
    Pass next();
    // A pass finished: each sampler's render time in it (0 for one not rendered).
    void finished(const Pass& pass, double secondsA, double secondsB);

    int spp(int which) const { return track_[which].spp; }
    double seconds(int which) const { return track_[which].seconds; }

    // A progressive sampler's passes grow while they take less than this,
    // after `seconds` of its render time (pass_scheduler.cpp says why).
    static constexpr double kLongestPass = 2.0;
    static double passSecondsAfter(double seconds);

  private:
    struct Track {
        bool progressive = true;
        int spp = 0, batch = 1;
        double lastPass = 0, seconds = 0;
    };
    int nextCount(Track& t, double lastPassSeconds) const;

    EqualBy equal_;
    bool hasB_;
    int maxSpp_;
    std::array<Track, 2> track_;
};

}  // namespace pathlab::view
