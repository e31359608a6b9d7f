// GET /api/points (docs/view.md): the points a pixel of the image shown
// receives from sampler A or B in two dimensions, with their power spectrum —
// `pathlab points` for the pixel under the cursor.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "view/view_session.h"

namespace pathlab::view {

// The page asks for at most this many points: the spectrum of N points costs
// about min(16·N², 2·10^8) operations (spectrumFrequency).
constexpr int kMaxViewPoints = 4096;

// The query's parameters as text; empty: not given.
struct PointsQuery {
    std::string pixel, dims = "0,1", count, which = "a";
};

// The points of the session's sampler (which: a or b) at its seed, built for
// `count` samples per pixel (default: the frame's spp, at most
// kMaxViewPoints) of an image the frame's size. Throws InputError naming the
// parameter that is missing, malformed or out of range.
nlohmann::json pointsJson(const SessionStatus& status, const PointsQuery& query);

}  // namespace pathlab::view
