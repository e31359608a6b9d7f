// Helpers for the scene tests: a scratch directory and small file writers.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scene/scene.h"

namespace pathlab {

// A closed cube [−1,1]³ of two-sided emitters with Lambertian albedo `albedo`,
// seen from inside: the radiance is Le·Σ_{k=0}^{D} a^k after D bounces, Le/(1−a)
// in the limit (the "white furnace").
inline SceneDescription furnaceCube(float albedo, float emission) {
    SceneDescription s;
    s.materials.push_back(Material{"wall", MaterialType::Diffuse, Vec3f(albedo)});
    Mesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back({i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f});
    // Faces as quads of corner indices, each split into two triangles.
    const unsigned faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                  {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& f : faces)
        for (unsigned idx : {f[0], f[1], f[2], f[0], f[2], f[3]}) m.indices.push_back(idx);
    m.emission = Vec3f(emission);
    m.twoSided = true;
    s.meshes.push_back(m);
    s.camera = Camera{{0.1f, 0.2f, 0.3f}, {0.5f, 0.1f, -1.0f}, {0, 1, 0}, 70};
    s.resolution = {24, 24};
    return s;
}

namespace test {

// A fresh directory removed when the test ends.
class ScratchDir {
  public:
    ScratchDir() {
        static std::atomic<int> counter{0};
        path_ =
            std::filesystem::temp_directory_path() /
            ("pathlab-scene-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    const std::filesystem::path& path() const { return path_; }
    std::string write(const std::string& name, const std::string& text) const {
        const auto p = path_ / name;
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }

  private:
    std::filesystem::path path_;
};

// The message of the InputError `f` throws; fails the test when it throws
// nothing or something else.
template <typename F>
std::string inputErrorOf(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected InputError, got: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected InputError, nothing was thrown";
    return {};
}

}  // namespace test
}  // namespace pathlab
