// The scenes built into pathlab, reachable by name from loadScene().
#pragma once

#include "scene/scene.h"

namespace pathlab {

// The Cornell box exactly as published by the Cornell Program of Computer
// Graphics (see cornell_box.cpp for the data and its conventions).
SceneDescription cornellBoxScene();

// The 0 A.D. wolf on a floor under two area lights (see wolf_scene.cpp). Finds
// or fetches its data with locateWolfAssets(); throws InputError when that fails.
SceneDescription wolfScene();

}  // namespace pathlab
