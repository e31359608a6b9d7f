// Seeds as text: CLI11 clamps an out-of-range unsigned integer ("-1",
// "99999999999999999999") to the largest value without a word, so the command
// line and the Python module read a seed as text and convert it here.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>

#include "core/error.h"

namespace pathlab {

// A seed: a decimal integer from 0 to 2^64−1, nothing else.
inline uint64_t parseSeed(const std::string& text, const std::string& option = "--seed") {
    uint64_t v = 0;
    const char* end = text.data() + text.size();
    const auto [at, ec] = std::from_chars(text.data(), end, v);
    if (text.empty() || ec != std::errc() || at != end)
        throw InputError(option + " must be an integer between 0 and " +
                         std::to_string(UINT64_MAX) + ", got '" + text + "'");
    return v;
}

}  // namespace pathlab
