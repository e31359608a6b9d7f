// Checks every loader's output before the renderer sees it, so a bad scene is
// one clear InputError instead of NaN pixels or a crash deep in a render.
#pragma once

#include <string>

#include "scene/scene.h"

namespace pathlab {

// Throws InputError ("<source>: <what is wrong>") when the scene has:
// no geometry; a camera whose eye equals its target, whose up is parallel to
// the view direction or whose fovY is outside (0°, 180°); a non-positive
// resolution; non-finite or out-of-range positions, normals, UVs, indices,
// colours or material parameters; a material or texture index that does not
// exist; a degenerate (zero-area) triangle on an emitting mesh (a light is
// sampled by area, so a zero-area triangle has no valid pdf); a sphere with
// non-positive radius; an instanced object's mesh that emits (instanced shapes
// are never lights; pbrt-v4 does not support them either) or is broken as a
// top-level one would be;
// an instance of an object that does not exist, or whose transform is
// non-finite or singular. Degenerate triangles on non-emitting meshes are left
// alone: they are common in real meshes and harmless to the renderer.
void validateScene(const SceneDescription& scene, const std::string& source);

}  // namespace pathlab
