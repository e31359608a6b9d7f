// The built-in Cornell box. Geometry: the Cornell Program of Computer
// Graphics' measured data (millimetres), vertex for vertex as Embree's
// cornell_box.obj gives it, with its winding: (p1−p0)×(p2−p0) of the walls
// points into the box, of the blocks out of them. The front wall is left out, as in the photograph;
// the ceiling is one quad without a hole, at y = 548.8, and the light quad hangs 0.8 mm below it at
// y = 548, so nothing of the ceiling occludes it. Block footprints are part of the floor in the
// data; facing down, they close the blocks from below and are never visible. Materials, light and
// camera: MISSION.md.
#include <array>

#include "scene/builtin_scenes.h"
#include "scene/mesh_utils.h"

namespace pathlab {
namespace {

enum : int { kWhite = 0, kRed = 1, kGreen = 2, kLightMaterial = 3 };

struct Quad {
    const char* mesh;
    int material;
    std::array<Vec3f, 4> p;
};

// In the data's order; consecutive quads of one mesh name form one mesh.
constexpr Quad kQuads[] = {
    {"floor", kWhite, {{{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}}}},
    {"floor", kWhite, {{{290, 0, 114}, {240, 0, 272}, {82, 0, 225}, {130, 0, 65}}}},
    {"floor", kWhite, {{{472, 0, 406}, {314, 0, 456}, {265, 0, 296}, {423, 0, 247}}}},
    {"ceiling",
     kWhite,
     {{{556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}}}},
    {"back_wall",
     kWhite,
     {{{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}}}},
    {"green_wall", kGreen, {{{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}}}},
    {"red_wall",
     kRed,
     {{{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}}}},
    {"short_block", kWhite, {{{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}}}},
    {"short_block", kWhite, {{{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}}}},
    {"short_block", kWhite, {{{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}}}},
    {"short_block", kWhite, {{{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}}}},
    {"short_block", kWhite, {{{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}}}},
    {"tall_block", kWhite, {{{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}}}},
    {"tall_block", kWhite, {{{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}}}},
    {"tall_block", kWhite, {{{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}}}},
    {"tall_block", kWhite, {{{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}}}},
    {"tall_block", kWhite, {{{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}}}},
    // In this order (p1−p0)×(p2−p0) = (0, −13650, 0): the light faces down.
    {"light",
     kLightMaterial,
     {{{343, 548, 227}, {343, 548, 332}, {213, 548, 332}, {213, 548, 227}}}},
};

Material diffuse(const char* name, Vec3f albedo) {
    Material m;
    m.name = name;
    m.type = MaterialType::Diffuse;
    m.albedo = albedo;
    return m;
}

}  // namespace

SceneDescription cornellBoxScene() {
    SceneDescription s;
    s.name = "cornell-box";
    s.camera.eye = {278, 273, -800};
    s.camera.target = {278, 273, 0};
    s.camera.up = {0, 1, 0};
    s.camera.fovY = 37.5f;
    s.resolution = {512, 512};
    s.materials = {diffuse("white", {0.725f, 0.71f, 0.68f}), diffuse("red", {0.63f, 0.065f, 0.05f}),
                   diffuse("green", {0.14f, 0.45f, 0.091f}),
                   // The light reflects nothing: it is an emitter only.
                   diffuse("light", Vec3f(0.0f))};
    for (const Quad& q : kQuads) {
        if (s.meshes.empty() || s.meshes.back().name != q.mesh) {
            Mesh m;
            m.name = q.mesh;
            m.material = q.material;
            s.meshes.push_back(std::move(m));
        }
        appendQuad(s.meshes.back(), q.p[0], q.p[1], q.p[2], q.p[3]);
    }
    Mesh& light = s.meshes.back();
    light.emission = {17, 12, 4};
    light.twoSided = false;
    return s;
}

}  // namespace pathlab
