// Images compared as the tests that claim "bit for bit" mean it: the same size
// and the same bytes of every float (so -0 differs from 0, and NaN payloads
// count).
#pragma once

#include <cstring>

#include "core/image.h"

namespace pathlab::testing {

inline bool sameBytes(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.rgb.size() == b.rgb.size() &&
           (a.rgb.empty() ||
            std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0);
}

}  // namespace pathlab::testing
