// The JSON of GET /api/status (docs/view.md).
#pragma once

#include <nlohmann/json.hpp>

#include "view/view_session.h"

namespace pathlab::view {

nlohmann::json statusJson(const SessionStatus& status);

}  // namespace pathlab::view
