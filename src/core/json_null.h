// A number that may be absent, as JSON: the value, or null. Studies, their
// cache and `compare --json` all write measurements that a cell, a region or
// a metric may lack.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

namespace pathlab {

template <class JsonType = nlohmann::ordered_json>
JsonType orNull(const std::optional<double>& v) {
    return v ? JsonType(*v) : JsonType(nullptr);
}

// The inverse: null is absent; any other value must be a number.
inline std::optional<double> optionalNumber(const nlohmann::json& value) {
    if (value.is_null()) return std::nullopt;
    return value.get<double>();
}

}  // namespace pathlab
