#include "scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "core/error.h"
#include "scene/texture_loader.h"

namespace pathlab {
namespace fs = std::filesystem;
namespace {

// tinyobjloader reads "nan" and "inf" as 0 without a word, so coordinates are
// checked on the text first: every number on a v/vn/vt line must be finite.
void checkCoordinates(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
        std::istringstream s(line);
        std::string keyword;
        s >> keyword;
        if (keyword != "v" && keyword != "vn" && keyword != "vt") continue;
        std::string token;
        while (s >> token) {
            char* end = nullptr;
            const double value = std::strtod(token.c_str(), &end);
            if (end != token.c_str() + token.size() || !std::isfinite(float(value)))
                throw InputError("OBJ file '" + path + "' line " + std::to_string(lineNo) +
                                 ": vertex coordinate '" + token + "' is not a finite number");
        }
    }
}

Vec3f rgb(const tinyobj::real_t c[3]) {
    return {float(c[0]), float(c[1]), float(c[2])};
}

Vec3f conductorK(Vec3f reflectance) {
    auto k = [](float r) {
        r = std::clamp(r, 0.0f, 0.99f);
        return 2 * std::sqrt(r / (1 - r));
    };
    return {k(reflectance.x), k(reflectance.y), k(reflectance.z)};
}

Material convertMaterial(const tinyobj::material_t& m, SceneDescription& scene,
                         const fs::path& baseDir, std::map<std::string, int>& textureCache) {
    Material out;
    out.name = m.name;
    const Vec3f kd = rgb(m.diffuse), ks = rgb(m.specular);
    const int illum = m.illum;
    if (m.metallic >= 0.5f) {
        out.type = MaterialType::Conductor;
        out.eta = Vec3f(1.0f);
        out.k = conductorK(kd);
        out.roughness = float(m.roughness) * float(m.roughness);
    } else if (illum == 4 || illum == 6 || illum == 7 || illum == 9) {
        out.type = MaterialType::Dielectric;
        out.albedo = Vec3f(1.0f);
        out.ior = m.ior > 1 ? float(m.ior) : 1.5f;
        out.roughness = 0;
    } else if ((illum == 3 || illum == 5 || illum == 8) && m.shininess >= 1000) {
        out.type = MaterialType::Mirror;
        out.albedo = isBlack(ks) ? Vec3f(1.0f) : ks;
    } else if (illum == 3 || illum == 5 || illum == 8) {
        out.type = MaterialType::Conductor;
        out.eta = Vec3f(1.0f);
        out.k = conductorK(isBlack(ks) ? Vec3f(1.0f) : ks);
        out.roughness = std::sqrt(2.0f / (std::max(float(m.shininess), 0.0f) + 2.0f));
    } else {
        out.type = MaterialType::Diffuse;
        out.albedo = kd;
        if (!m.diffuse_texname.empty()) {
            const std::string texPath = (baseDir / m.diffuse_texname).lexically_normal().string();
            auto it = textureCache.find(texPath);
            if (it == textureCache.end()) {
                scene.textures.push_back(loadTexture(texPath));
                it = textureCache.emplace(texPath, int(scene.textures.size()) - 1).first;
            }
            out.texture = it->second;
        }
    }
    return out;
}

struct VertexKey {
    int v, t, n;
    bool operator==(const VertexKey&) const = default;
};
struct VertexKeyHash {
    size_t operator()(const VertexKey& k) const {
        return std::hash<uint64_t>()((uint64_t(uint32_t(k.v)) << 32) ^
                                     (uint64_t(uint32_t(k.t)) << 16) ^ uint64_t(uint32_t(k.n)));
    }
};

}  // namespace

size_t appendObj(SceneDescription& scene, const std::string& path, int materialOverride) {
    if (!fs::is_regular_file(path)) throw InputError("OBJ file '" + path + "' does not exist");
    checkCoordinates(path);
    const fs::path baseDir = fs::path(path).parent_path();
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = baseDir.string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string why = reader.Error();
        while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
        throw InputError("OBJ file '" + path + "': " + why);
    }
    // A missing MTL is only a warning to tinyobjloader; for a scene it means
    // every material is lost, so it is an error here.
    if (reader.Warning().find("not found") != std::string::npos) {
        std::string why = reader.Warning();
        why = why.substr(0, why.find('\n'));
        throw InputError("OBJ file '" + path + "': " + why);
    }

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3,
                 nt = attrib.texcoords.size() / 2;

    // Materials: the MTL's, then one default for faces without any.
    const int firstMaterial = int(scene.materials.size());
    std::map<std::string, int> textureCache;
    const auto& mtl = reader.GetMaterials();
    if (materialOverride < 0)
        for (const auto& m : mtl)
            scene.materials.push_back(convertMaterial(m, scene, baseDir, textureCache));
    int defaultMaterial = -1;

    // Faces grouped by material id, in order of first use.
    struct Group {
        Mesh mesh;
        std::unordered_map<VertexKey, uint32_t, VertexKeyHash> vertexOf;
        bool allNormals = true, allUvs = true;
        std::vector<VertexKey> keys;
    };
    std::map<int, Group> groups;
    std::vector<int> order;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const auto& indices = shape.mesh.indices;
        for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            if (shape.mesh.num_face_vertices[f] != 3)
                throw InputError("OBJ file '" + path + "': a face of '" + shape.name +
                                 "' could not be triangulated");
            const int mtlId = materialOverride >= 0 ? -2 : shape.mesh.material_ids[f];
            auto [it, added] = groups.try_emplace(mtlId);
            if (added) order.push_back(mtlId);
            Group& g = it->second;
            for (int c = 0; c < 3; ++c) {
                const tinyobj::index_t& idx = indices[3 * f + c];
                if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv ||
                    (idx.normal_index >= 0 && size_t(idx.normal_index) >= nn) ||
                    (idx.texcoord_index >= 0 && size_t(idx.texcoord_index) >= nt) ||
                    idx.normal_index < -1 || idx.texcoord_index < -1)
                    throw InputError("OBJ file '" + path + "': face " + std::to_string(f) +
                                     " of '" + shape.name + "' has an index out of range (" +
                                     std::to_string(nv) + " vertices)");
                const VertexKey key{idx.vertex_index, idx.texcoord_index, idx.normal_index};
                g.allNormals &= key.n >= 0;
                g.allUvs &= key.t >= 0;
                auto [vit, isNew] = g.vertexOf.try_emplace(key, uint32_t(g.keys.size()));
                if (isNew) g.keys.push_back(key);
                g.mesh.indices.push_back(vit->second);
            }
        }
    }

    const std::string stem = fs::path(path).stem().string();
    for (int id : order) {
        Group& g = groups[id];
        Mesh& mesh = g.mesh;
        for (const VertexKey& k : g.keys) {
            const float* p = &attrib.vertices[3 * size_t(k.v)];
            mesh.positions.push_back({p[0], p[1], p[2]});
            if (g.allNormals) {
                const float* n = &attrib.normals[3 * size_t(k.n)];
                const Vec3f normal{n[0], n[1], n[2]};
                // A zero normal cannot shade; fall back to flat shading.
                if (dot(normal, normal) == 0)
                    g.allNormals = false;
                else
                    mesh.normals.push_back(normalize(normal));
            }
            if (g.allUvs) {
                const float* t = &attrib.texcoords[2 * size_t(k.t)];
                mesh.uvs.push_back({t[0], 1.0f - t[1]});
            }
        }
        if (!g.allNormals) mesh.normals.clear();
        if (!g.allUvs) mesh.uvs.clear();
        if (id == -2) {
            mesh.material = materialOverride;
            mesh.name = stem;
        } else if (id >= 0 && size_t(id) < mtl.size()) {
            mesh.material = firstMaterial + id;
            mesh.name = stem + "/" + mtl[id].name;
            mesh.emission = rgb(mtl[id].emission);
        } else {
            if (defaultMaterial < 0) {
                Material m;
                m.name = stem + "/default";
                m.albedo = Vec3f(0.8f);
                scene.materials.push_back(m);
                defaultMaterial = int(scene.materials.size()) - 1;
            }
            mesh.material = defaultMaterial;
            mesh.name = stem;
        }
        scene.meshes.push_back(std::move(mesh));
    }
    return order.size();
}

}  // namespace pathlab
