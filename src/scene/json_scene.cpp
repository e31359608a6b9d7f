#include "scene/json_scene.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "scene/json_node.h"
#include "scene/light_selection.h"
#include "scene/mesh_utils.h"
#include "scene/obj_loader.h"

namespace pathlab {
namespace jsonscene {

fs::path Node::file() const {
    const std::string s = string();
    if (s.empty()) fail("empty file name");
    const fs::path p = fs::path(s).is_absolute() ? fs::path(s) : ctx_.baseDir / s;
    std::error_code ec;
    const fs::file_status status = fs::status(p, ec);
    if (!fs::exists(status)) fail("file '" + p.string() + "' does not exist");
    if (!fs::is_regular_file(status)) fail("'" + p.string() + "' is not a regular file");
    return p;
}

Affine parseTransform(const Node& n) {
    n.keys({"scale", "rotate", "translate"});
    // Applied in the order scale, rotate(s), translate.
    Affine xf;
    if (n.has("scale")) {
        const Node s = n["scale"];
        const Vec3f v = s.json().is_number() ? Vec3f(s.number()) : s.vec3();
        if (v.x == 0 || v.y == 0 || v.z == 0) s.fail("scale must not be zero");
        xf = Affine::scaling(v);
    }
    if (n.has("rotate")) {
        const Node r = n["rotate"];
        auto one = [](const Node& rot) {
            rot.keys({"axis", "degrees"});
            const Vec3f axis = rot["axis"].vec3();
            if (dot(axis, axis) == 0) rot["axis"].fail("axis must not be zero");
            return Affine::rotation(axis, rot["degrees"].number());
        };
        if (r.json().is_array())
            for (size_t i = 0; i < r.size(); ++i) xf = one(r.at(i)) * xf;
        else
            xf = one(r) * xf;
    }
    if (n.has("translate")) xf = Affine::translation(n["translate"].vec3()) * xf;
    return xf;
}

namespace {

// A list of polygons with `corners` vertices each: [[[x,y,z], ...], ...].
void appendPolygons(const Node& list, int corners, Mesh& mesh) {
    for (size_t i = 0; i < list.size(); ++i) {
        const Node poly = list.at(i);
        if (poly.size() != size_t(corners))
            poly.fail("expected " + std::to_string(corners) + " vertices, got " +
                      std::to_string(poly.size()));
        Vec3f p[4];
        for (int c = 0; c < corners; ++c) p[c] = poly.at(c).vec3();
        if (corners == 4)
            appendQuad(mesh, p[0], p[1], p[2], p[3]);
        else
            appendTriangle(mesh, p[0], p[1], p[2]);
    }
}

void parseMesh(const Node& n, size_t index, Builder& b) {
    if (n.has("obj")) {
        n.keys({"obj", "material", "transform", "alpha"});
        const size_t first = b.scene.meshes.size();
        const int forced = n.has("material") ? b.material(n["material"]) : -1;
        const Node obj = n["obj"];
        const std::string path = obj.file().string();  // fails with its own prefix
        try {
            appendObj(b.scene, path, forced);
        } catch (const InputError& e) {
            obj.fail(e.what());
        }
        // As for an OBJ given as the scene itself: a file with no faces (empty,
        // or not OBJ at all, whose lines tinyobjloader skips) is a mistake.
        size_t triangles = 0;
        for (size_t i = first; i < b.scene.meshes.size(); ++i)
            triangles += b.scene.meshes[i].triangleCount();
        if (triangles == 0) obj.fail("OBJ file '" + path + "' has no faces");
        if (n.has("transform")) {
            const Affine xf = parseTransform(n["transform"]);
            for (size_t i = first; i < b.scene.meshes.size(); ++i)
                transformMesh(b.scene.meshes[i], xf);
        }
        if (n.has("alpha")) {
            const int alpha = alphaParam(n["alpha"], b);
            for (size_t i = first; i < b.scene.meshes.size(); ++i)
                b.scene.meshes[i].alphaTexture = alpha;
        }
        return;
    }
    n.keys({"name", "material", "quads", "triangles", "positions", "indices", "normals", "uvs",
            "emission", "twoSided", "transform", "alpha"});
    Mesh mesh;
    mesh.name = n.has("name") ? n["name"].string() : "mesh" + std::to_string(index);
    mesh.material = b.material(n["material"]);
    const bool indexed = n.has("positions") || n.has("indices");
    if (indexed && (n.has("quads") || n.has("triangles")))
        n.fail("give either 'positions' and 'indices' or 'quads'/'triangles', not both");
    if (indexed) {
        const Node pos = n["positions"], idx = n["indices"];
        for (size_t i = 0; i < pos.size(); ++i) mesh.positions.push_back(pos.at(i).vec3());
        if (idx.size() % 3 != 0) idx.fail("the number of indices must be a multiple of 3");
        for (size_t i = 0; i < idx.size(); ++i) {
            const Node e = idx.at(i);
            if (!e.json().is_number_unsigned())
                e.fail(std::string("expected a non-negative integer, got ") + typeName(e.json()));
            const uint64_t v = e.json().get<uint64_t>();
            if (v >= mesh.positions.size())
                e.fail("index " + std::to_string(v) + " out of range (" +
                       std::to_string(mesh.positions.size()) + " positions)");
            mesh.indices.push_back(uint32_t(v));
        }
        if (n.has("normals")) {
            const Node nn = n["normals"];
            if (nn.size() != mesh.positions.size()) nn.fail("needs one normal per position");
            for (size_t i = 0; i < nn.size(); ++i) {
                const Vec3f v = nn.at(i).vec3();
                if (dot(v, v) == 0) nn.at(i).fail("normal must not be zero");
                mesh.normals.push_back(normalize(v));
            }
        }
        if (n.has("uvs")) {
            const Node uv = n["uvs"];
            if (uv.size() != mesh.positions.size()) uv.fail("needs one UV per position");
            for (size_t i = 0; i < uv.size(); ++i) {
                const Node e = uv.at(i);
                if (e.size() != 2) e.fail("expected [u, v]");
                mesh.uvs.push_back({e.at(0).number(), e.at(1).number()});
            }
        }
    } else {
        if (n.has("normals") || n.has("uvs"))
            n.fail("'normals' and 'uvs' need the indexed form ('positions' and 'indices')");
        if (!n.has("quads") && !n.has("triangles"))
            n.fail("needs 'quads', 'triangles', 'positions' and 'indices', or 'obj'");
        if (n.has("quads")) appendPolygons(n["quads"], 4, mesh);
        if (n.has("triangles")) appendPolygons(n["triangles"], 3, mesh);
    }
    if (n.has("emission")) mesh.emission = n["emission"].colour();
    if (n.has("twoSided")) mesh.twoSided = n["twoSided"].boolean();
    if (n.has("transform")) transformMesh(mesh, parseTransform(n["transform"]));
    if (n.has("alpha")) {
        if (!isBlack(mesh.emission)) n["alpha"].fail("an emitting mesh cannot be cut out");
        mesh.alphaTexture = alphaParam(n["alpha"], b);
    }
    b.scene.meshes.push_back(std::move(mesh));
}

// Lights reflect nothing unless given a material: they are emitters only.
int blackMaterial(Builder& b) {
    const std::string name = "(light)";
    auto it = b.materialIndex.find(name);
    if (it != b.materialIndex.end()) return it->second;
    Material m;
    m.name = name;
    m.albedo = Vec3f(0.0f);
    b.scene.materials.push_back(m);
    return b.materialIndex[name] = int(b.scene.materials.size()) - 1;
}

// An image environment map (docs/scene-format.md): pbrt-v4's equal-area
// octahedral layout, its +z world +z.
void parseEnvironmentMap(const Node& n, Builder& b) {
    n.keys({"file", "scale", "sampling"});
    const Node f = n["file"];
    const std::string path = f.file().lexically_normal().string();
    Image img;
    try {
        img = readImage(path);
    } catch (const InputError& e) {
        f.fail(e.what());
    }
    if (img.width != img.height)
        f.fail("'" + path + "' is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
               ", not square: not an equal-area octahedral map");
    for (float v : img.rgb)
        if (!std::isfinite(v) || v < 0)
            f.fail("'" + path + "' has a negative, NaN or infinite pixel");
    const float scale = n.has("scale") ? n["scale"].positive() : 1;
    EnvironmentImage env;
    if (n.has("sampling")) {
        const std::string how = n["sampling"].string();
        if (how != "luminance" && how != "uniform")
            n["sampling"].fail("must be \"luminance\" or \"uniform\", got '" + how + "'");
        env.uniformSampling = how == "uniform";
    }
    env.width = img.width;
    env.height = img.height;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) env.texels.push_back(img.at(x, y) * scale);
    b.scene.environmentMap = std::move(env);
}

// A point, spot or distant light (docs/scene-format.md), as pbrt-v4's.
void parsePunctualLight(const Node& n, const std::string& type, Builder& b) {
    PunctualLight l;
    const auto unit = [](const Node& d) {
        const Vec3f v = d.vec3();
        if (!(length(v) > 0)) d.fail("a direction must not be zero");
        return normalize(v);
    };
    if (type == "point") {
        n.keys({"name", "type", "position", "intensity"});
        l.type = PunctualLightType::Point;
        l.position = n["position"].vec3();
        l.intensity = n["intensity"].colour();
    } else if (type == "spot") {
        n.keys(
            {"name", "type", "position", "direction", "intensity", "coneAngle", "coneDeltaAngle"});
        l.type = PunctualLightType::Spot;
        l.position = n["position"].vec3();
        l.direction = unit(n["direction"]);
        l.intensity = n["intensity"].colour();
        const float cone = n.has("coneAngle") ? n["coneAngle"].number() : 30;
        const float delta = n.has("coneDeltaAngle") ? n["coneDeltaAngle"].number() : 5;
        if (!(cone > 0 && cone <= 180)) n["coneAngle"].fail("must be in (0, 180] degrees");
        if (!(delta >= 0 && delta <= cone))
            n[n.has("coneDeltaAngle") ? "coneDeltaAngle" : "coneAngle"].fail(
                "coneDeltaAngle must be in [0, coneAngle]");
        setSpotCone(l, cone, delta);
    } else {
        n.keys({"name", "type", "direction", "radiance"});
        l.type = PunctualLightType::Distant;
        l.direction = unit(n["direction"]);
        l.radiance = n["radiance"].colour();
    }
    b.scene.punctualLights.push_back(l);
}

void parseLight(const Node& n, size_t index, Builder& b) {
    const std::string lightType = n["type"].string();
    if (lightType == "point" || lightType == "spot" || lightType == "distant")
        return parsePunctualLight(n, lightType, b);
    n.keys({"name", "type", "vertices", "emission", "twoSided", "material"});
    Mesh mesh;
    mesh.name = n.has("name") ? n["name"].string() : "light" + std::to_string(index);
    const Node typeNode = n["type"];
    const std::string type = typeNode.string();
    int corners = 0;
    if (type == "quad")
        corners = 4;
    else if (type == "triangle")
        corners = 3;
    else
        typeNode.fail("unknown light type '" + type + "' (quad, triangle, point, spot, distant)");
    const Node v = n["vertices"];
    if (v.size() != size_t(corners))
        v.fail("a " + type + " light needs " + std::to_string(corners) + " vertices, got " +
               std::to_string(v.size()));
    Vec3f p[4];
    for (int c = 0; c < corners; ++c) p[c] = v.at(c).vec3();
    if (corners == 4)
        appendQuad(mesh, p[0], p[1], p[2], p[3]);
    else
        appendTriangle(mesh, p[0], p[1], p[2]);
    if (!(length(triangleNormalArea(p[0], p[1], p[2])) > 0) ||
        (corners == 4 && !(length(triangleNormalArea(p[0], p[2], p[3])) > 0)))
        v.fail("the light has zero area");
    mesh.emission = n["emission"].colour();
    if (isBlack(mesh.emission)) n["emission"].fail("a light's emission must not be black");
    if (n.has("twoSided")) mesh.twoSided = n["twoSided"].boolean();
    mesh.material = n.has("material") ? b.material(n["material"]) : blackMaterial(b);
    b.scene.meshes.push_back(std::move(mesh));
}

void parseSphere(const Node& n, Builder& b) {
    n.keys({"center", "radius", "material", "emission", "twoSided"});
    Sphere s;
    s.center = n["center"].vec3();
    s.radius = n["radius"].positive();
    s.material = b.material(n["material"]);
    if (n.has("emission")) s.emission = n["emission"].colour();
    if (n.has("twoSided")) s.twoSided = n["twoSided"].boolean();
    b.scene.spheres.push_back(s);
}

Json parseText(const std::string& text, const std::string& source) {
    // nlohmann keeps the last of duplicate keys silently; a duplicate is almost
    // always a mistake, so the parser callback tracks each object's keys.
    std::vector<std::set<std::string>> open;
    std::string duplicate;
    auto callback = [&](int, Json::parse_event_t event, Json& parsed) {
        switch (event) {
            case Json::parse_event_t::object_start:
                open.emplace_back();
                break;
            case Json::parse_event_t::object_end:
                if (!open.empty()) open.pop_back();
                break;
            case Json::parse_event_t::key:
                if (!open.empty() && !open.back().insert(parsed.get<std::string>()).second &&
                    duplicate.empty())
                    duplicate = parsed.get<std::string>();
                break;
            default:
                break;
        }
        return true;
    };
    try {
        Json j = Json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/true);
        if (!duplicate.empty()) throw InputError(source + ": duplicate key '" + duplicate + "'");
        return j;
    } catch (const Json::exception& e) {
        // A syntax error or a number too large for a double (out_of_range.406).
        // what() is "[json.exception.parse_error.101] parse error at line L, column C: ...".
        std::string why = e.what();
        if (const auto p = why.find("] "); p != std::string::npos) why = why.substr(p + 2);
        throw InputError(source + ": invalid JSON: " + why);
    }
}

}  // namespace
}  // namespace jsonscene

namespace fs = std::filesystem;
using jsonscene::Builder;
using jsonscene::Context;
using jsonscene::Json;
using jsonscene::Node;

SceneDescription parseJsonScene(const std::string& text, const fs::path& baseDir,
                                const std::string& source) {
    using namespace jsonscene;
    const Json j = parseText(text, source);
    const Context ctx{source, baseDir};
    const Node root(j, "", ctx);
    root.keys({"name", "credit", "camera", "resolution", "environment", "environmentMap",
               "textures", "materials", "meshes", "lights", "spheres", "lightSampler"});
    Builder b;
    SceneDescription& s = b.scene;
    s.name = root.has("name") ? root["name"].string() : fs::path(source).stem().string();
    if (root.has("credit")) s.credit = root["credit"].string();

    const Node cam = root["camera"];
    cam.keys({"eye", "target", "up", "fovY"});
    s.camera.eye = cam["eye"].vec3();
    s.camera.target = cam["target"].vec3();
    if (cam.has("up")) s.camera.up = cam["up"].vec3();
    s.camera.fovY = cam["fovY"].number();
    if (!(s.camera.fovY > 0 && s.camera.fovY < 180))
        cam["fovY"].fail("must be in (0, 180) degrees");
    if (s.camera.eye.x == s.camera.target.x && s.camera.eye.y == s.camera.target.y &&
        s.camera.eye.z == s.camera.target.z)
        cam["target"].fail("camera target equals its eye");

    if (root.has("resolution")) {
        const Node r = root["resolution"];
        if (r.size() != 2) r.fail("expected [width, height]");
        s.resolution = {r.at(0).imageSide(), r.at(1).imageSide()};
    }
    if (root.has("environment")) s.environment = root["environment"].colour();
    if (root.has("environmentMap")) parseEnvironmentMap(root["environmentMap"], b);
    if (root.has("lightSampler")) {
        const Node ls = root["lightSampler"];
        s.defaults.lightSampler = ls.string();
        if (!lightSelectionNamed(s.defaults.lightSampler))
            ls.fail(std::string("expected one of ") + lightSelectionNames() + ", got '" +
                    s.defaults.lightSampler + "'");
    }

    if (root.has("textures")) parseTextures(root["textures"], b);
    if (root.has("materials")) parseMaterials(root["materials"], b);
    if (root.has("meshes")) {
        const Node meshes = root["meshes"];
        for (size_t i = 0; i < meshes.size(); ++i) parseMesh(meshes.at(i), i, b);
    }
    if (root.has("lights")) {
        const Node lights = root["lights"];
        for (size_t i = 0; i < lights.size(); ++i) parseLight(lights.at(i), i, b);
    }
    if (root.has("spheres")) {
        const Node spheres = root["spheres"];
        for (size_t i = 0; i < spheres.size(); ++i) parseSphere(spheres.at(i), b);
    }
    if (s.meshes.empty() && s.spheres.empty())
        throw InputError(source + ": the scene has no meshes, lights or spheres");
    return s;
}

SceneDescription loadJsonScene(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot open scene file '" + path + "'");
    std::ostringstream text;
    text << in.rdbuf();
    return parseJsonScene(text.str(), fs::path(path).parent_path(), path);
}

namespace {

// The shortest decimal that reads back as the same float, so written scenes
// say 0.725 rather than 0.7250000238418579.
double shortest(float v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
}
Json toJson(Vec3f v) {
    return Json::array({shortest(v.x), shortest(v.y), shortest(v.z)});
}

Json coatingJson(const Coating& c) {
    Json o = {{"ior", shortest(c.eta)},
              {"roughness", shortest(c.roughness)},
              {"thickness", shortest(c.thickness)},
              {"albedo", toJson(c.albedo)},
              {"g", shortest(c.g)},
              {"maxDepth", c.maxDepth},
              {"samples", c.nSamples}};
    if (c.roughnessV >= 0) o["roughnessV"] = shortest(c.roughnessV);
    return o;
}

}  // namespace

std::string sceneToJson(const SceneDescription& s) {
    if (!s.environmentMap.empty())
        throw InputError("cannot write scene '" + s.name +
                         "': its environment map has no file to refer to");
    Json j;
    j["name"] = s.name;
    if (!s.credit.empty()) j["credit"] = s.credit;
    j["camera"] = {{"eye", toJson(s.camera.eye)},
                   {"target", toJson(s.camera.target)},
                   {"up", toJson(s.camera.up)},
                   {"fovY", shortest(s.camera.fovY)}};
    j["resolution"] = {s.resolution.x, s.resolution.y};
    j["environment"] = toJson(s.environment);
    if (!s.defaults.lightSampler.empty()) j["lightSampler"] = s.defaults.lightSampler;
    // Material names must be unique keys; repeated names get their index appended.
    std::vector<std::string> names;
    std::set<std::string> used;
    Json mats = Json::object();
    for (size_t i = 0; i < s.materials.size(); ++i) {
        const Material& m = s.materials[i];
        std::string name = m.name.empty() ? "material" + std::to_string(i) : m.name;
        if (!used.insert(name).second) {
            name.append(1, '#').append(std::to_string(i));
            used.insert(name);
        }
        names.push_back(name);
        Json o;
        if (m.normalMap >= 0 || m.displacementTexture >= 0)
            throw InputError("cannot write material '" + m.name +
                             "': bump and normal maps have no file to refer to");
        if (m.albedoTexture >= 0 || m.transmittanceTexture >= 0 || m.roughnessTexture >= 0 ||
            m.roughnessVTexture >= 0 || m.amountTexture >= 0)
            throw InputError("cannot write material '" + m.name +
                             "': its texture graph is not written");
        switch (m.type) {
            case MaterialType::Diffuse:
                if (m.texture >= 0)
                    throw InputError("cannot write material '" + m.name +
                                     "': textures have no file to refer to");
                o = {{"type", "diffuse"}, {"albedo", toJson(m.albedo)}};
                break;
            case MaterialType::Mirror:
                o = {{"type", "mirror"}, {"albedo", toJson(m.albedo)}};
                break;
            case MaterialType::Dielectric:
                o = {{"type", "dielectric"}, {"ior", shortest(m.ior)}};
                if (m.roughness > 0) o["roughness"] = shortest(m.roughness);
                if (m.roughnessV >= 0) o["roughnessV"] = shortest(m.roughnessV);
                break;
            case MaterialType::Conductor:
                o = {{"type", "conductor"},
                     {"eta", toJson(m.eta)},
                     {"k", toJson(m.k)},
                     {"roughness", shortest(m.roughness)}};
                if (m.roughnessV >= 0) o["roughnessV"] = shortest(m.roughnessV);
                break;
            case MaterialType::ThinDielectric:
                o = {{"type", "thindielectric"}, {"ior", shortest(m.ior)}};
                break;
            case MaterialType::DiffuseTransmission:
                o = {{"type", "diffusetransmission"},
                     {"reflectance", toJson(m.albedo)},
                     {"transmittance", toJson(m.transmittance)}};
                break;
            case MaterialType::Mix:
                o = {{"type", "mix"}, {"amount", shortest(m.amount)}, {"materials", Json::array()}};
                break;
            case MaterialType::Interface:
                o = {{"type", "interface"}};
                break;
            case MaterialType::CoatedDiffuse:
                o = {{"type", "coateddiffuse"},
                     {"reflectance", toJson(m.albedo)},
                     {"coating", coatingJson(m.coating)}};
                break;
            case MaterialType::CoatedConductor:
                o = {{"type", "coatedconductor"},
                     {"eta", toJson(m.eta)},
                     {"k", toJson(m.k)},
                     {"roughness", shortest(m.roughness)},
                     {"coating", coatingJson(m.coating)}};
                if (m.roughnessV >= 0) o["roughnessV"] = shortest(m.roughnessV);
                break;
        }
        mats[name] = o;
    }
    // Mixes name their parts, whose names are all known now.
    for (size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].type == MaterialType::Mix)
            for (int part : s.materials[i].mix)
                mats[names[i]]["materials"].push_back(names.at(size_t(part)));
    j["materials"] = mats;
    Json meshes = Json::array();
    for (const Mesh& m : s.meshes) {
        if (m.alphaTexture >= 0)
            throw InputError("cannot write mesh '" + m.name + "': its alpha is not written");
        Json o;
        o["name"] = m.name;
        o["material"] = names.at(size_t(m.material));
        Json pos = Json::array();
        for (const Vec3f& p : m.positions) pos.push_back(toJson(p));
        o["positions"] = pos;
        o["indices"] = m.indices;
        if (!m.normals.empty()) {
            Json nn = Json::array();
            for (const Vec3f& n : m.normals) nn.push_back(toJson(n));
            o["normals"] = nn;
        }
        if (!m.uvs.empty()) {
            Json uv = Json::array();
            for (const Vec2f& t : m.uvs) uv.push_back({shortest(t.x), shortest(t.y)});
            o["uvs"] = uv;
        }
        if (!isBlack(m.emission)) o["emission"] = toJson(m.emission);
        if (m.twoSided) o["twoSided"] = true;
        meshes.push_back(o);
    }
    j["meshes"] = meshes;
    if (!s.punctualLights.empty()) {
        Json lights = Json::array();
        for (const PunctualLight& l : s.punctualLights) {
            if (l.type == PunctualLightType::Point)
                lights.push_back({{"type", "point"},
                                  {"position", toJson(l.position)},
                                  {"intensity", toJson(l.intensity)}});
            else if (l.type == PunctualLightType::Spot)
                lights.push_back({{"type", "spot"},
                                  {"position", toJson(l.position)},
                                  {"direction", toJson(l.direction)},
                                  {"intensity", toJson(l.intensity)},
                                  {"coneAngle", shortest(l.coneAngle)},
                                  {"coneDeltaAngle", shortest(l.coneDeltaAngle)}});
            else
                lights.push_back({{"type", "distant"},
                                  {"direction", toJson(l.direction)},
                                  {"radiance", toJson(l.radiance)}});
        }
        j["lights"] = lights;
    }
    if (!s.spheres.empty()) {
        Json spheres = Json::array();
        for (const Sphere& sp : s.spheres) {
            Json js = {{"center", toJson(sp.center)},
                       {"radius", shortest(sp.radius)},
                       {"material", names.at(size_t(sp.material))}};
            if (!isBlack(sp.emission)) js["emission"] = toJson(sp.emission);
            if (sp.twoSided) js["twoSided"] = true;
            spheres.push_back(js);
        }
        j["spheres"] = spheres;
    }
    return j.dump(2) + "\n";
}

}  // namespace pathlab
