// The Shape directive (pbrt-v4 File Format, "Shapes"): every shape becomes a
// triangle mesh in world space, except whole spheres under a similarity
// transform, which stay exact (Embree spheres). Orientation follows pbrt-v4:
// a triangle's front is (p1−p0)×(p2−p0) as authored, kept through mirroring
// transforms (transformSwapsHandedness) and flipped by ReverseOrientation;
// where the mesh has normals, its front is the side they point to
// (pbrt-v4's Triangle takes the geometric normal's side from the shading
// normal). An area light emits from the front (or both sides when twosided).
#include <algorithm>
#include <cmath>

#include "scene/mesh_utils.h"
#include "scene/pbrt/loop_subdivision.h"
#include "scene/pbrt/parser_state.h"
#include "scene/pbrt/ply_mesh.h"
#include "scene/pbrt/shape_meshes.h"

namespace pathlab::pbrt {
namespace {

void checkIndices(const std::vector<int>& indices, size_t vertices, size_t perFace,
                  const std::string& shapeName, const SourceLocation& where) {
    if (indices.size() % perFace != 0)
        throw errorAt(where, shapeName + ": \"integer indices\" holds " +
                                 std::to_string(indices.size()) + " values, not a multiple of " +
                                 std::to_string(perFace));
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] < 0 || size_t(indices[i]) >= vertices)
            throw errorAt(where, shapeName + ": index " + std::to_string(indices[i]) + " (entry " +
                                     std::to_string(i) + ") is out of range (" +
                                     std::to_string(vertices) + " vertices)");
}

// Indices of a mesh given by P (and optional N, uv) and "integer indices".
std::vector<uint32_t> meshIndices(const ParamSet& ps, size_t vertices, size_t perFace,
                                  const std::string& shapeName, const SourceLocation& where) {
    std::vector<int> indices = ps.getInts("indices");
    if (indices.empty()) {
        if (vertices != perFace)
            throw errorAt(where, shapeName +
                                     ": \"integer indices\" is missing (needed unless "
                                     "there are exactly " +
                                     std::to_string(perFace) + " vertices)");
        for (size_t i = 0; i < perFace; ++i) indices.push_back(int(i));
    }
    checkIndices(indices, vertices, perFace, shapeName, where);
    return {indices.begin(), indices.end()};
}

void checkPerVertex(size_t count, size_t vertices, const char* what, const std::string& shapeName,
                    const SourceLocation& where) {
    if (count != 0 && count != vertices)
        throw errorAt(where, shapeName + ": " + std::to_string(count) + " " + what + " for " +
                                 std::to_string(vertices) + " vertices");
}

// Turns each triangle's front towards its vertices' mean normal.
void faceNormalsForward(Mesh& m) {
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
        const uint32_t a = m.indices[i], b = m.indices[i + 1], c = m.indices[i + 2];
        const Vec3f ng = triangleNormalArea(m.positions[a], m.positions[b], m.positions[c]);
        if (dot(ng, m.normals[a] + m.normals[b] + m.normals[c]) < 0)
            std::swap(m.indices[i + 1], m.indices[i + 2]);
    }
}

// Leaves out an emitter's triangles of no area (lightTriangleHasArea, the
// test validateScene makes). They emit no power, but a light is
// sampled by area, where they would have no density.
void dropDegenerateTriangles(Mesh& m) {
    const Vec3f ext = meshBounds(m).extent();
    std::vector<uint32_t> kept;
    kept.reserve(m.indices.size());
    for (size_t t = 0; t < m.triangleCount(); ++t)
        if (lightTriangleHasArea(m, t, dot(ext, ext)))
            kept.insert(kept.end(), m.indices.begin() + long(3 * t),
                        m.indices.begin() + long(3 * t) + 3);
    m.indices = std::move(kept);
}

// A (partial) sphere as pbrt-v4 parameterises it (PBRT 4th ed., 6.2):
// φ in [0, phiMax], z in [zMin, zMax]; normals outward.
Mesh tessellatedSphere(float r, float zMin, float zMax, float phiMaxDeg) {
    const double thetaA = std::acos(std::clamp(double(std::min(zMin, zMax)) / r, -1.0, 1.0));
    const double thetaB = std::acos(std::clamp(double(std::max(zMin, zMax)) / r, -1.0, 1.0));
    const double phiMax = std::clamp(double(phiMaxDeg), 0.0, 360.0) * 3.14159265358979323846 / 180;
    const int nu = 128, nv = 64;
    Mesh m;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            const double phi = phiMax * i / nu, theta = thetaA + (thetaB - thetaA) * j / nv;
            const Vec3f n{float(std::sin(theta) * std::cos(phi)),
                          float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))};
            m.positions.push_back(n * r);
            m.normals.push_back(n);
            m.uvs.push_back({float(i) / nu, float(j) / nv});
        }
    const auto at = [&](int i, int j) { return uint32_t(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const uint32_t q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
            for (const auto& t : tris) {
                const Vec3f p0 = m.positions[q[t[0]]], p1 = m.positions[q[t[1]]],
                            p2 = m.positions[q[t[2]]];
                if (length(triangleNormalArea(p0, p1, p2)) <= 0) continue;  // at a pole
                m.indices.insert(m.indices.end(), {q[t[0]], q[t[1]], q[t[2]]});
            }
        }
    faceNormalsForward(m);
    return m;
}

// A whole sphere stays exact when the transform keeps it a sphere: its 3×3
// part a rotation (or mirror) times one scale.
std::optional<float> similarityScale(const Matrix4& m) {
    Vec3f col[3];
    for (int j = 0; j < 3; ++j) col[j] = {float(m.m[0][j]), float(m.m[1][j]), float(m.m[2][j])};
    const float s = length(col[0]);
    for (int j = 0; j < 3; ++j)
        if (std::abs(length(col[j]) - s) > 1e-5f * s) return std::nullopt;
    if (std::abs(dot(col[0], col[1])) > 1e-5f * s * s ||
        std::abs(dot(col[0], col[2])) > 1e-5f * s * s ||
        std::abs(dot(col[1], col[2])) > 1e-5f * s * s)
        return std::nullopt;
    return s;
}

// The shape's material, light and transform, then into the scene (or the
// object being defined).
void place(ImportState& st, Mesh mesh, const std::string& shapeName, const SourceLocation& where,
           size_t primitives = 0, double shapeArea = 0) {
    const GraphicsState& gs = st.gs;
    if (!gs.ctm.isAffine())
        throw errorAt(where, "Shape \"" + shapeName + "\" under a projective transform");
    transformMesh(mesh, gs.ctm.toAffine());
    if (gs.reverseOrientation) {
        for (Vec3f& n : mesh.normals) n = -n;
        flipWinding(mesh);
    }
    mesh.material = gs.material >= 0 ? gs.material : st.defaultMaterial();
    mesh.alphaTexture = st.shapeAlpha;
    mesh.name = shapeName + "@" + std::to_string(where.line);
    if (gs.areaLight) {
        if (st.currentObject >= 0) {
            st.unsupported(where,
                           "an area light inside an object (instanced shapes cannot emit, "
                           "as in pbrt-v4)",
                           "a shape that does not emit");
        } else {
            mesh.emission =
                areaLightEmission(st, *gs.areaLight, mesh,
                                  primitives ? primitives : mesh.triangleCount(), shapeArea, where);
            mesh.twoSided = gs.areaLight->twoSided;
            dropDegenerateTriangles(mesh);
            if (!mesh.normals.empty()) faceNormalsForward(mesh);
        }
    }
    if (mesh.indices.empty()) return;  // nothing to render (e.g. a zero-angle disk)
    st.addTriangles(mesh.triangleCount(), where);
    SceneDescription& s = st.result.scene;
    if (st.currentObject >= 0)
        s.objects[size_t(st.currentObject)].meshes.push_back(std::move(mesh));
    else
        s.meshes.push_back(std::move(mesh));
}

// pbrt-v4's shape "alpha": a float or a float texture; 1 (the default) is
// opaque. Anything else becomes a float texture node cutting the shape.
int shapeAlpha(ImportState& st, const ParamSet& ps) {
    if (const auto t = floatTextureParam(st, ps, "alpha")) return *t;
    const float a = ps.getFloat("alpha", 1);
    if (a >= 1) return -1;
    ShadingTexture constant;
    constant.isFloat = true;
    constant.value = Vec3f(a);
    st.result.scene.shadingTextures.push_back(constant);
    return int(st.result.scene.shadingTextures.size()) - 1;
}

Mesh triangleMesh(const ParamSet& ps, const SourceLocation& where) {
    Mesh m;
    m.positions = ps.getPoint3s("P");
    if (m.positions.empty()) throw errorAt(where, "trianglemesh: \"point3 P\" is missing");
    m.indices = meshIndices(ps, m.positions.size(), 3, "trianglemesh", where);
    m.normals = ps.getNormals("N");
    m.uvs = ps.getPoint2s("uv");
    checkPerVertex(m.normals.size(), m.positions.size(), "normals", "trianglemesh", where);
    checkPerVertex(m.uvs.size(), m.positions.size(), "uvs", "trianglemesh", where);
    return m;
}

}  // namespace

void shape(ImportState& st, const std::string& type, const ParamSet& given,
           const SourceLocation& where, const std::string& includingDir) {
    const ParamSet ps = given.withDefaults(st.gs.attributes["shape"]);
    // Tangents and per-face indices only matter to features pathlab lacks
    // (anisotropic shading frames, per-face textures).
    ps.ignore("S"), ps.ignore("faceIndices");
    st.shapeAlpha = shapeAlpha(st, ps);
    if (type == "trianglemesh") {
        place(st, triangleMesh(ps, where), type, where);
    } else if (type == "plymesh") {
        const std::string file = ps.getString("filename", "");
        if (file.empty()) throw errorAt(where, "plymesh: \"string filename\" is missing");
        if (ps.find("displacement"))
            st.unsupported(where, "plymesh displacement", "the undisplaced mesh");
        ps.ignore("edgelength");
        const std::string path = st.resolveFile(file, includingDir, where);
        Mesh m;
        try {
            m = loadPlyMesh(path);
        } catch (const InputError& e) {
            throw errorAt(where, e.what());
        }
        place(st, std::move(m), type, where);
    } else if (type == "sphere") {
        const float r = ps.getFloat("radius", 1);
        const float zMin = ps.getFloat("zmin", -r), zMax = ps.getFloat("zmax", r);
        const float phiMax = ps.getFloat("phimax", 360);
        if (!(r > 0)) throw errorAt(where, "sphere: radius must be positive");
        const bool whole = zMin <= -r && zMax >= r && phiMax >= 360;
        const auto scale = similarityScale(st.gs.ctm);
        // An exact sphere faces outwards; a reversed one (inside out, as for
        // a dielectric's eta) is made of triangles, which can face in, and so
        // is an emitting one under a mirror (pbrt-v4 flips its normal) or in
        // an object (which cannot emit: place() says so). A cut-out one too
        // (the cut-out filters triangles).
        const bool exactLight =
            !st.gs.areaLight || (st.currentObject < 0 && !st.gs.ctm.swapsHandedness());
        if (whole && scale && st.gs.ctm.isAffine() && exactLight && !st.gs.reverseOrientation &&
            st.shapeAlpha < 0) {
            Sphere sp{st.gs.ctm.point({0, 0, 0}), r * *scale,
                      st.gs.material >= 0 ? st.gs.material : st.defaultMaterial()};
            if (st.gs.areaLight) {
                // pbrt-v4 scales `power` by the object-space area (Sphere::Area).
                sp.emission =
                    areaLightEmission(st, *st.gs.areaLight, Mesh{}, 1, 4 * kPi * r * r, where);
                sp.twoSided = st.gs.areaLight->twoSided;
            }
            SceneDescription& s = st.result.scene;
            if (st.currentObject >= 0)
                s.objects[size_t(st.currentObject)].spheres.push_back(sp);
            else
                s.spheres.push_back(sp);
        } else {
            // Partial, sheared, or an emitter that may face inwards.
            const double zLow = std::max(zMin, -r), zHigh = std::min(zMax, r);
            place(st, tessellatedSphere(r, zMin, zMax, phiMax), type, where, 1,
                  std::min(phiMax, 360.0f) * kPi / 180 * r * (zHigh - zLow));
        }
    } else if (type == "disk") {
        const float radius = ps.getFloat("radius", 1), inner = ps.getFloat("innerradius", 0);
        if (!(radius > 0) || inner < 0 || inner >= radius)
            throw errorAt(where, "disk: needs 0 <= innerradius < radius");
        place(st,
              tessellateDisk(ps.getFloat("height", 0), radius, inner, ps.getFloat("phimax", 360),
                             256),
              type, where, 1,
              std::min(ps.getFloat("phimax", 360), 360.0f) * kPi / 180 * 0.5 *
                  (double(radius) * radius - double(inner) * inner));
    } else if (type == "bilinearmesh") {
        const std::vector<Vec3f> P = ps.getPoint3s("P");
        if (P.empty()) throw errorAt(where, "bilinearmesh: \"point3 P\" is missing");
        const std::vector<uint32_t> idx = meshIndices(ps, P.size(), 4, type, where);
        const std::vector<Vec3f> N = ps.getNormals("N");
        const std::vector<Vec2f> uv = ps.getPoint2s("uv");
        checkPerVertex(N.size(), P.size(), "normals", type, where);
        checkPerVertex(uv.size(), P.size(), "uvs", type, where);
        if (ps.find("emissionfilename"))
            st.unsupported(where, "bilinearmesh emissionfilename", "uniform emission");
        place(st, bilinearPatchMesh(P, idx, N, uv, 16), type, where, idx.size() / 4);
    } else if (type == "loopsubdiv") {
        const std::vector<Vec3f> P = ps.getPoint3s("P");
        if (P.empty()) throw errorAt(where, "loopsubdiv: \"point3 P\" is missing");
        const std::vector<uint32_t> idx = meshIndices(ps, P.size(), 3, type, where);
        const int levels = ps.getInt("levels", 3);
        if (levels < 0 || levels > 8) throw errorAt(where, "loopsubdiv: levels must be in [0, 8]");
        st.addTriangles((idx.size() / 3) << (2 * levels), where, false);
        Mesh m;
        try {
            m = loopSubdivide(P, idx, levels);
        } catch (const InputError& e) {
            throw errorAt(where, std::string("loopsubdiv: ") + e.what());
        }
        place(st, std::move(m), type, where);
    } else if (type == "curve" || type == "cylinder" || type == "cone" || type == "hyperboloid" ||
               type == "paraboloid") {
        st.unsupported(where, "shape '" + type + "'", "nothing (the shape is left out)");
        for (const Param& p : ps.all()) p.used = true;
        return;
    } else {
        throw errorAt(where, "unknown shape '" + type + "'");
    }
    st.checkUnused(ps, "Shape \"" + type + "\"");
}

}  // namespace pathlab::pbrt
