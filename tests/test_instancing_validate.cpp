// validateScene on instanced objects: their shapes are checked as top-level
// ones are, they may not emit, and instances must name an existing object
// with a finite, invertible transform.
#include <gtest/gtest.h>

#include <limits>

#include "instancing_test_util.h"
#include "scene/validate.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

using test::inputErrorOf;
using test::instancedScene;

std::string problem(const SceneDescription& s) {
    return inputErrorOf([&] { validateScene(s, "s"); });
}

bool mentions(const std::string& message, const std::string& what) {
    return message.find(what) != std::string::npos;
}

TEST(InstancingValidation, AcceptsTheInstancedScene) {
    EXPECT_NO_THROW(validateScene(instancedScene(), "s"));
}

TEST(InstancingValidation, RejectsAnEmittingMeshInAnObject) {
    SceneDescription s = instancedScene();
    s.objects[0].meshes[1].emission = Vec3f(5.0f);
    const std::string message = problem(s);
    EXPECT_TRUE(mentions(message, "object 'thing'")) << message;
    EXPECT_TRUE(mentions(message, "emitting mesh 'box'")) << message;
    EXPECT_TRUE(mentions(message, "cannot be area lights")) << message;
    // Also in an object no instance places: the scene is wrong either way.
    s = instancedScene();
    s.objects[2].meshes[0].emission = Vec3f(1.0f);
    EXPECT_TRUE(mentions(problem(s), "object 'unused'"));
}

TEST(InstancingValidation, ChecksObjectShapesLikeTopLevelOnes) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    SceneDescription s = instancedScene();
    s.objects[0].meshes[0].indices[7] = 1u << 30;
    std::string message = problem(s);
    EXPECT_TRUE(mentions(message, "object 'thing' mesh 'blob'")) << message;
    EXPECT_TRUE(mentions(message, "out of range")) << message;
    s = instancedScene();
    s.objects[0].meshes[0].positions[3].z = nan;
    EXPECT_TRUE(mentions(problem(s), "non-finite position"));
    s = instancedScene();
    s.objects[0].meshes[0].normals[3] = Vec3f(0.0f);
    EXPECT_TRUE(mentions(problem(s), "zero or non-finite normal"));
    s = instancedScene();
    s.objects[0].meshes[0].uvs.pop_back();
    EXPECT_TRUE(mentions(problem(s), "UVs for"));
    s = instancedScene();
    s.objects[0].meshes[1].material = 9;
    EXPECT_TRUE(mentions(problem(s), "material 9"));
    s = instancedScene();
    s.objects[1].spheres[1].radius = -1;
    message = problem(s);
    EXPECT_TRUE(mentions(message, "object 'balls' sphere 1")) << message;
    EXPECT_TRUE(mentions(message, "non-positive radius")) << message;
    s = instancedScene();
    s.objects[1].spheres[0].material = -2;
    EXPECT_TRUE(mentions(problem(s), "material -2"));
    // An object without a name is named by its index.
    s = instancedScene();
    s.objects[0].name.clear();
    s.objects[0].meshes[0].positions[0].x = nan;
    EXPECT_TRUE(mentions(problem(s), "object '0' mesh 'blob'"));
}

TEST(InstancingValidation, ChecksInstances) {
    const float inf = std::numeric_limits<float>::infinity();
    SceneDescription s = instancedScene();
    s.instances[3].object = 3;
    std::string message = problem(s);
    EXPECT_TRUE(mentions(message, "instance 3 refers to object 3 which does not exist")) << message;
    s.instances[3].object = -1;
    EXPECT_TRUE(mentions(problem(s), "object -1 which does not exist"));
    s = instancedScene();
    s.instances[2].objectToWorld.m[1][2] = inf;
    message = problem(s);
    EXPECT_TRUE(mentions(message, "instance 2 of object 'thing' has a non-finite transform"))
        << message;
    s = instancedScene();
    s.instances[0].objectToWorld.t.y = -inf;
    EXPECT_TRUE(mentions(problem(s), "non-finite translation"));
    s = instancedScene();
    s.instances[1].objectToWorld = s.instances[1].objectToWorld * Affine::scaling({1, 0, 1});
    message = problem(s);
    EXPECT_TRUE(mentions(message, "instance 1 of object 'thing' has a singular transform"))
        << message;
    // Two parallel rows: singular without a zero scale.
    s = instancedScene();
    Affine& xf = s.instances[0].objectToWorld;
    for (int c = 0; c < 3; ++c) xf.m[2][c] = 2 * xf.m[0][c];
    EXPECT_TRUE(mentions(problem(s), "singular transform"));
    // Tiny but invertible (an object modelled in micrometres) is fine.
    s = instancedScene();
    s.instances[0].objectToWorld = Affine::scaling({1e-6f, 1e-6f, 1e-6f});
    EXPECT_NO_THROW(validateScene(s, "s"));
}

TEST(InstancingValidation, InstancesCountAsGeometry) {
    SceneDescription s = instancedScene();
    s.meshes.clear();
    s.environment = Vec3f(1.0f);
    EXPECT_NO_THROW(validateScene(s, "s"));
    // Only the unused object's instances left, and that object emptied: nothing to see.
    s.instances = {{2, Affine{}}};
    s.objects[2].meshes.clear();
    EXPECT_TRUE(mentions(problem(s), "no geometry"));
}

}  // namespace
}  // namespace pathlab
