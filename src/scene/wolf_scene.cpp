// The built-in wolf: 0 A.D.'s wolf (© 2010 Wildfire Games, CC-BY-SA-3.0) on a
// wide grey floor, seen from its right side and a little above, under two
// one-sided rectangular area lights of different size and power plus a dim
// sky. The large key light, high over the camera's side, casts a soft shadow
// under the wolf; the small, brighter fill light, low at the tail end, lights
// the flank and hind legs and casts a second, sharper shadow, so the
// light-choice dimension of a sampler matters.
#include <cmath>

#include "core/error.h"
#include "scene/assets.h"
#include "scene/builtin_scenes.h"
#include "scene/mesh_utils.h"
#include "scene/pmd_loader.h"
#include "scene/texture_loader.h"

namespace pathlab {
namespace {

// A one-sided rectangle centred at `center`, `width` × `height`, emitting
// towards `facing` (its front side: (p1−p0)×(p2−p0) ∥ facing).
Mesh rectangleLight(const char* name, Vec3f center, Vec3f facing, float width, float height,
                    Vec3f radiance, int material) {
    const Frame f(normalize(facing));
    // Frame's s × t = n, so corners in the order (−s−t, +s−t, +s+t, −s+t) wind
    // around n counter-clockwise.
    const Vec3f u = f.s * (0.5f * width), v = f.t * (0.5f * height);
    Mesh m;
    m.name = name;
    m.material = material;
    m.emission = radiance;
    appendQuad(m, center - u - v, center + u - v, center + u + v, center - u + v);
    return m;
}

}  // namespace

SceneDescription wolfScene() {
    const WolfAssets assets = locateWolfAssets();
    SceneDescription s;
    s.name = "wolf";
    s.credit = "Wolf model and texture © 2010 Wildfire Games (0 A.D.), CC-BY-SA-3.0";
    s.resolution = {512, 512};

    enum : int { kFur = 0, kFloor = 1, kLight = 2 };
    Material fur;
    fur.name = "fur";
    fur.albedo = Vec3f(1.0f);  // the texture carries the colour
    fur.texture = 0;
    s.textures.push_back(loadTexture(assets.texture.string()));
    Material floor;
    floor.name = "floor";
    floor.albedo = Vec3f(0.5f);
    Material light;
    light.name = "light";
    light.albedo = Vec3f(0.0f);  // emitters only
    s.materials = {fur, floor, light};

    Mesh wolf = readPmd(assets.mesh.string());
    wolf.name = "wolf";
    wolf.material = kFur;
    const Bounds3f b = meshBounds(wolf);
    s.meshes.push_back(std::move(wolf));

    // The floor at the paws (y ≈ 0), wide enough that its edge stays out of
    // sight; facing up.
    Mesh ground;
    ground.name = "floor";
    ground.material = kFloor;
    const float y0 = b.lo.y, r = 30.0f;
    appendQuad(ground, {-r, y0, -r}, {-r, y0, r}, {r, y0, r}, {r, y0, -r});
    s.meshes.push_back(std::move(ground));

    // Key: 3 × 3 at 5.5 above the floor, over the camera's side and towards
    // the head; fill: 0.6 × 0.6, low at the tail end on the camera's side, just
    // out of the picture, with about 5× the radiance but 1/5 of the power.
    const Vec3f c = b.center();
    const Vec3f keyPos{3.0f, 5.5f, -1.5f}, fillPos{2.5f, 1.6f, 4.5f};
    s.meshes.push_back(rectangleLight("key light", keyPos, c - keyPos, 3.0f, 3.0f,
                                      Vec3f(9.0f, 8.6f, 8.0f), kLight));
    s.meshes.push_back(rectangleLight("fill light", fillPos, c - fillPos, 0.6f, 0.6f,
                                      Vec3f(40.0f, 44.0f, 52.0f), kLight));
    s.environment = Vec3f(0.06f, 0.07f, 0.08f);

    // From the wolf's right side (+x; its snout points to −z, which is then
    // image right), a little above — steep enough that the floor, not the
    // horizon, is the whole background — framing the body with floor around.
    s.camera.target = {c.x, c.y - 0.2f, c.z};
    s.camera.eye = {c.x + 7.5f, c.y + 3.3f, c.z - 1.5f};
    s.camera.up = {0, 1, 0};
    s.camera.fovY = 30.0f;
    return s;
}

}  // namespace pathlab
