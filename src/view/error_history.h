// Live error against a reference image: MSE and HDR-ꟻLIP (as a study measures
// them) of A and B after passes at log-spaced sample counts — the first pass
// at or beyond each power of two — so the curves are evenly spaced on a
// log-log plot and measuring costs a shrinking share of the render.
#pragma once

#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "core/image.h"
#include "metrics/flip.h"

namespace pathlab::view {

// What GET /api/image?map= shows instead of an image.
enum class ErrorMapKind { RelativeSquared, Flip };

struct ErrorPoint {
    int spp = 0;   // A's
    int sppB = 0;  // B's: spp at equal spp, its own count at equal time
    double mseA = 0, flipA = 0, mseB = 0, flipB = 0;  // B: 0 without a compare sampler
};

class ErrorHistory {
  public:
    // `reference`: linear RGB of the image the passes converge to.
    explicit ErrorHistory(std::shared_ptr<const Image> reference);
    ~ErrorHistory();

    const Image& reference() const { return *reference_; }
    // Does a pass that brings A or B to `spp` get measured? (The first at or
    // past the next power of two since the last one measured.)
    bool due(int spp) const { return spp >= nextSpp_; }
    // Measures A at sppA and B (null without a compare sampler) at sppB, and
    // appends the point.
    void measure(int sppA, const Image& a, int sppB, const Image* b);
    void clear();  // a restart
    // Per pixel, a value in [0, 1] for a colour map: HDR-ꟻLIP's own error
    // (as measured), or the relative squared error (t − r)² / (r² + ε),
    // averaged over the channels, on a log scale: 10^-4 … 1 to 0 … 1.
    // Safe from any thread: it reads only the reference.
    std::vector<float> errorMap(const Image& test, ErrorMapKind kind) const;
    const std::vector<ErrorPoint>& points() const { return points_; }

  private:
    std::shared_ptr<const Image> reference_;
    std::unique_ptr<flip::PreparedReference> flip_;
    std::vector<ErrorPoint> points_;
    int nextSpp_ = 1;
};

// {"spp": [...], "a": {"mse": [...], "flip": [...]}, "b": {...}}: empty arrays
// without a history, "b" empty without a compare sampler.
nlohmann::json errorJson(const std::vector<ErrorPoint>& points, bool hasB);

}  // namespace pathlab::view
