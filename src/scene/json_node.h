// The reading side of pathlab's JSON scene format shared by its parts
// (json_scene.cpp: the scene, shapes and lights; json_materials.cpp:
// materials; json_textures.cpp: the texture graph): a JSON value that knows
// its position in the document, so that every error names its key, and the
// scene being built. Internal to the JSON reader.
#pragma once

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/affine.h"
#include "core/error.h"
#include "core/image.h"
#include "scene/scene.h"

namespace pathlab::jsonscene {
namespace fs = std::filesystem;

// Keeps the keys in file order, so materials are numbered as written.
using Json = nlohmann::ordered_json;

inline const char* typeName(const Json& j) {
    if (j.is_number()) return "a number";
    if (j.is_string()) return "a string";
    if (j.is_boolean()) return "a boolean";
    if (j.is_array()) return "an array";
    if (j.is_object()) return "an object";
    return "null";
}

struct Context {
    std::string source;
    fs::path baseDir;
};

// A JSON value with its position in the document ("meshes[2].material"), so
// every error names the key it is about.
class Node {
  public:
    Node(const Json& j, std::string path, const Context& ctx)
        : j_(j), path_(std::move(path)), ctx_(ctx) {}

    const Json& json() const { return j_; }
    const std::string& path() const { return path_; }

    [[noreturn]] void fail(const std::string& message) const {
        throw InputError(ctx_.source + ": " + (path_.empty() ? "" : path_ + ": ") + message);
    }

    void requireObject() const {
        if (!j_.is_object()) fail(std::string("expected an object, got ") + typeName(j_));
    }
    // Every key must be one of `allowed` or `more`.
    void keys(std::initializer_list<std::string_view> allowed,
              std::span<const std::string_view> more = {}) const {
        requireObject();
        for (const auto& [key, value] : j_.items()) {
            bool ok = false;
            for (std::string_view a : allowed) ok |= key == a;
            for (std::string_view a : more) ok |= key == a;
            if (ok) continue;
            std::string list;
            for (std::string_view a : allowed) {
                if (!list.empty()) list += ", ";
                list += a;
            }
            for (std::string_view a : more) list += ", " + std::string(a);
            fail("unknown key '" + key + "' (expected one of: " + list + ")");
        }
    }
    bool has(const char* key) const { return j_.is_object() && j_.contains(key); }
    Node operator[](const char* key) const {
        requireObject();
        if (!j_.contains(key)) fail(std::string("missing required key '") + key + "'");
        return Node(j_.at(key), join(key), ctx_);
    }
    size_t size() const {
        if (!j_.is_array()) fail(std::string("expected an array, got ") + typeName(j_));
        return j_.size();
    }
    Node at(size_t i) const { return Node(j_.at(i), path_ + "[" + std::to_string(i) + "]", ctx_); }

    float number() const {
        if (!j_.is_number()) fail(std::string("expected a number, got ") + typeName(j_));
        const float v = j_.get<float>();
        if (!std::isfinite(v)) fail("number out of range");
        return v;
    }
    float positive() const {
        const float v = number();
        if (!(v > 0)) fail("must be positive");
        return v;
    }
    // An image side: the same limit as `render --size`, so that a scene file
    // cannot ask for an image the renderer cannot hold.
    int imageSide() const {
        if (!j_.is_number_integer()) fail(std::string("expected an integer, got ") + typeName(j_));
        const auto v = j_.get<int64_t>();
        if (v < 1 || v > kMaxImageSide)
            fail("must be between 1 and " + std::to_string(kMaxImageSide) + ", got " +
                 std::to_string(v));
        return int(v);
    }
    bool boolean() const {
        if (!j_.is_boolean()) fail(std::string("expected true or false, got ") + typeName(j_));
        return j_.get<bool>();
    }
    std::string string() const {
        if (!j_.is_string()) fail(std::string("expected a string, got ") + typeName(j_));
        return j_.get<std::string>();
    }
    Vec3f vec3() const {
        if (!j_.is_array() || j_.size() != 3 || !j_[0].is_number() || !j_[1].is_number() ||
            !j_[2].is_number())
            fail(std::string("expected an array of 3 numbers, got ") + typeName(j_));
        const Vec3f v{at(0).number(), at(1).number(), at(2).number()};
        return v;
    }
    // An RGB triple, or one number for grey; never negative.
    Vec3f colour() const {
        Vec3f c;
        if (j_.is_number())
            c = Vec3f(number());
        else if (j_.is_array() && j_.size() == 3)
            c = vec3();
        else
            fail(std::string("expected an RGB colour [r, g, b] or one number, got ") +
                 typeName(j_));
        if (c.x < 0 || c.y < 0 || c.z < 0) fail("colour components must not be negative");
        return c;
    }
    // An existing regular file, relative to the scene file's directory
    // (json_scene.cpp).
    fs::path file() const;

  private:
    std::string join(const char* key) const { return path_.empty() ? key : path_ + "." + key; }
    const Json& j_;
    std::string path_;
    const Context& ctx_;
};

struct Builder {
    SceneDescription scene;
    std::map<std::string, int> materialIndex;
    std::map<std::string, int> textureIndex;  // by path, loaded once
    // The "textures" section's named textures: node index in
    // scene.shadingTextures, and whether it is a float texture.
    struct NamedTexture {
        int node;
        bool isFloat;
    };
    std::map<std::string, NamedTexture> namedTextures;
    // The component names of the mix material parsed last, with their slot.
    struct MixPart {
        Node name;
        int slot;
    };
    std::vector<MixPart> mixParts;

    int material(const Node& n) {
        const std::string name = n.string();
        auto it = materialIndex.find(name);
        if (it == materialIndex.end()) n.fail("unknown material '" + name + "'");
        return it->second;
    }
};

// "transform" of meshes and texture spaces: scale, then rotate(s), then
// translate (json_scene.cpp).
Affine parseTransform(const Node& n);

// An image file named by node t, read once per file; `linear`: its code
// values taken as linear (a PNG's sRGB decoding undone), as maps need
// (json_materials.cpp).
int loadImage(const Node& t, Builder& b, bool linear);

// The "materials" section, in file order, mixes resolved (json_materials.cpp).
void parseMaterials(const Node& materials, Builder& b);

// The "textures" section (json_textures.cpp).
void parseTextures(const Node& textures, Builder& b);

// A parameter that may name a texture of the "textures" section: its node
// index when it is a string naming one of the right kind (float or not),
// −1 when it is a constant (read by the caller); an error naming the key
// otherwise (json_textures.cpp).
int textureParam(const Node& n, const Builder& b, bool isFloat);

// A shape's "alpha" (pbrt-v4's): a number in [0, 1] or a float texture;
// Mesh::alphaTexture, −1 for 1 (opaque) (json_textures.cpp).
int alphaParam(const Node& n, Builder& b);

}  // namespace pathlab::jsonscene
