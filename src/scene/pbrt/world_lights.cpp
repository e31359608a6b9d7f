// Lights (pbrt-v4 File Format, "Lights" and "Area Lights"; PBRT 4th ed.
// §12.1–12.5): diffuse area lights, point, spot and distant lights, and the
// constant infinite light, with RGB or blackbody emission; what pathlab does
// not render yet is reported as unsupported (substituted under --lenient).
//
// pbrt-v4 divides every light's spectrum by its photometric value
// (SpectrumToPhotometric), which for an RGB value is that of the colour
// space's illuminant: an RGB I or L renders as that RGB, and `power` /
// `illuminance` then scale a light whose RGB is taken as one nit.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/equal_area.h"
#include "core/image.h"
#include "scene/blackbody.h"
#include "scene/mesh_utils.h"
#include "scene/pbrt/parser_state.h"

namespace pathlab::pbrt {

namespace {

void markAllUsed(const ParamSet& ps) {
    for (const Param& p : ps.all()) p.used = true;
}

// A light's spectrum parameter as RGB (default: the illuminant, RGB 1),
// rejecting negative values.
Vec3f emissionParam(ImportState& st, const ParamSet& ps, const std::string& name,
                    const std::string& directive, const SourceLocation& where) {
    Vec3f value(1.0f);
    const Param* p = ps.find(name);
    if (p && p->type == ParamType::Blackbody) {
        if (p->numbers.size() != 1 || !(p->numbers[0] > 0))
            throw errorAt(p->where, "parameter '" + name +
                                        "': blackbody takes one positive temperature in kelvin");
        return blackbodyRgb(p->numbers[0]);
    }
    if (auto rgb = rgbParam(st, ps, name)) value = *rgb;
    if (value.x < 0 || value.y < 0 || value.z < 0)
        throw errorAt(where, directive + ": " + name + " must not be negative");
    return value;
}

// The unit world direction of the light-space vector v (the CTM's linear
// part; a non-uniform scale bends the cone, which pbrt-v4 measures in light
// space: such transforms are approximated).
Vec3f worldDirection(const ImportState& st, Vec3f v, const std::string& directive,
                     const SourceLocation& where) {
    const Vec3f w = st.gs.ctm.vector(v);
    const float len = length(w);
    if (!(len > 0) || !std::isfinite(len))
        throw errorAt(where, directive + ": 'from' and 'to' must be different points");
    return w / len;
}

PunctualLight pointLight(ImportState& st, const ParamSet& ps, const SourceLocation& where) {
    PunctualLight l;
    l.type = PunctualLightType::Point;
    l.intensity = emissionParam(st, ps, "I", "LightSource \"point\"", where);
    float scale = ps.getFloat("scale", 1);
    // pbrt-v4's PointLight::Create: power Φ spread over 4π steradians.
    const float power = ps.getFloat("power", -1);
    if (power > 0) scale *= power / float(4 * kPi);
    l.intensity *= scale;
    l.position = st.gs.ctm.point(ps.getPoint3("from").value_or(Vec3f(0.0f)));
    return l;
}

PunctualLight spotLight(ImportState& st, const ParamSet& ps, const SourceLocation& where) {
    const std::string directive = "LightSource \"spot\"";
    PunctualLight l;
    l.type = PunctualLightType::Spot;
    l.intensity = emissionParam(st, ps, "I", directive, where);
    const float cone = ps.getFloat("coneangle", 30), delta = ps.getFloat("conedeltaangle", 5);
    if (!(cone > 0 && cone <= 180))
        throw errorAt(where, directive + ": coneangle must be in (0, 180] degrees");
    if (!(delta >= 0 && delta <= cone))
        throw errorAt(where, directive + ": conedeltaangle must be in [0, coneangle]");
    setSpotCone(l, cone, delta);
    float scale = ps.getFloat("scale", 1);
    // pbrt-v4's SpotLight::Create: Φ over the cone, the falloff band counting half.
    const float power = ps.getFloat("power", -1);
    if (power > 0)
        scale *=
            power /
            float(2 * kPi * ((1 - l.cosFalloffStart) + (l.cosFalloffStart - l.cosFalloffEnd) / 2));
    l.intensity *= scale;
    const Vec3f from = ps.getPoint3("from").value_or(Vec3f(0.0f));
    const Vec3f to = ps.getPoint3("to").value_or(Vec3f(0, 0, 1));
    l.position = st.gs.ctm.point(from);
    l.direction = worldDirection(st, to - from, directive, where);
    return l;
}

PunctualLight distantLight(ImportState& st, const ParamSet& ps, const SourceLocation& where) {
    const std::string directive = "LightSource \"distant\"";
    PunctualLight l;
    l.type = PunctualLightType::Distant;
    l.radiance = emissionParam(st, ps, "L", directive, where);
    float scale = ps.getFloat("scale", 1);
    // pbrt-v4's DistantLight::Create: illuminance E on a patch facing the light.
    const float illuminance = ps.getFloat("illuminance", -1);
    if (illuminance > 0) scale *= illuminance;
    l.radiance *= scale;
    const Vec3f from = ps.getPoint3("from").value_or(Vec3f(0.0f));
    const Vec3f to = ps.getPoint3("to").value_or(Vec3f(0, 0, 1));
    l.direction = worldDirection(st, to - from, directive, where);
    return l;
}

// pbrt-v4's illuminance of a map on an upward (light-space +z) patch, as its
// LightBase::Create computes it: Σ over texels above the horizon of Y·cosθ,
// times 2π/N (sic: its texels each subtend 4π/N).
double upperHemisphereIlluminance(const Image& img) {
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const Vec3f w = equalAreaSquareToSphere(
                {(float(x) + 0.5f) / float(img.width), (float(y) + 0.5f) / float(img.height)});
            if (w.z > 0) sum += double(luminance(img.at(x, y))) * double(w.z);
        }
    return sum * 2 * kPi / double(img.width) / double(img.height);
}

// The map's light frame: the CTM's linear part (pbrt-v4's renderFromLight)
// and its inverse.
void setLightFrame(ImportState& st, EnvironmentImage& env, const SourceLocation& where) {
    const Matrix4& m = st.gs.ctm;
    for (int c = 0; c < 3; ++c)
        env.toWorld[c] = Vec3f(float(m.m[0][c]), float(m.m[1][c]), float(m.m[2][c]));
    const auto inv = m.inverse();
    if (!inv) throw errorAt(where, "LightSource \"infinite\": singular transform");
    for (int c = 0; c < 3; ++c)
        env.toLight[c] = Vec3f(float(inv->m[0][c]), float(inv->m[1][c]), float(inv->m[2][c]));
}

void imageInfiniteLight(ImportState& st, const ParamSet& ps, const std::string& file, float scale,
                        const SourceLocation& where) {
    const std::string directive = "LightSource \"infinite\"";
    if (!st.result.scene.environmentMap.empty())
        throw errorAt(where, directive + ": a second image environment map (pathlab takes one)");
    const Image img = readImage(st.resolveFile(file, st.mainDir, where));
    if (img.width != img.height)
        throw errorAt(where, directive + ": '" + file + "' is " + std::to_string(img.width) + "x" +
                                 std::to_string(img.height) +
                                 ", not square: not an equal-area octahedral map");
    for (float v : img.rgb)
        if (!std::isfinite(v) || v < 0)
            throw errorAt(where,
                          directive + ": '" + file +
                              "' has a negative, NaN or infinite pixel: not usable as a light");
    const float illuminance = ps.getFloat("illuminance", -1);
    if (illuminance > 0) {
        const double mapIlluminance = upperHemisphereIlluminance(img);
        if (mapIlluminance > 0) scale *= float(illuminance / mapIlluminance);
    }
    EnvironmentImage env;
    env.width = img.width;
    env.height = img.height;
    env.texels.resize(img.pixelCount());
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            env.texels[size_t(y) * size_t(img.width) + size_t(x)] = img.at(x, y) * scale;
    setLightFrame(st, env, where);
    st.result.scene.environmentMap = std::move(env);
}

void infiniteLight(ImportState& st, const ParamSet& ps, const SourceLocation& where) {
    const std::string directive = "LightSource \"infinite\"";
    const float scale = ps.getFloat("scale", 1);
    const std::string file = ps.getString("filename", "");
    if (ps.find("portal")) st.unsupported(where, "infinite light portals", "no portal");
    if (!file.empty()) {
        if (ps.find("L")) throw errorAt(where, directive + ": give either L or filename, not both");
        imageInfiniteLight(st, ps, file, scale, where);
        st.checkUnused(ps, directive);
        return;
    }
    Vec3f L = emissionParam(st, ps, "L", directive, where);
    // pbrt-v4: the RGB counts as one nit, which gives illuminance π on any patch.
    const float illuminance = ps.getFloat("illuminance", -1);
    if (illuminance > 0) L *= illuminance / float(kPi);
    st.checkUnused(ps, directive);
    if (st.currentObject >= 0)
        return st.unsupported(where, "a light inside ObjectBegin", "no light");
    st.result.scene.environment += L * scale;
}

}  // namespace

void areaLightSource(ImportState& st, const std::string& type, const ParamSet& given,
                     const SourceLocation& where) {
    if (type != "diffuse")
        throw errorAt(where, "unknown area light '" + type + "' (pbrt-v4 has \"diffuse\")");
    const ParamSet ps = given.withDefaults(st.gs.attributes["light"]);
    AreaLight light;
    light.where = where;
    // pbrt-v4: L defaults to the colour space's illuminant, which is RGB
    // (1, 1, 1), and an RGB L is normalised to its luminance's nits, which
    // leaves the RGB value itself.
    light.radiance = emissionParam(st, ps, "L", "AreaLightSource", where);
    light.radiance *= ps.getFloat("scale", 1);
    light.twoSided = ps.getBool("twosided", false);
    light.power = ps.getFloat("power", -1);
    if (ps.find("filename")) st.unsupported(where, "image area lights", "uniform emission");
    if (ps.find("alpha")) st.unsupported(where, "area light alpha", "an opaque light");
    st.checkUnused(ps, "AreaLightSource");
    st.gs.areaLight = light;
}

Vec3f areaLightEmission(ImportState& st, const AreaLight& light, const Mesh& mesh,
                        size_t primitives, double shapeArea, const SourceLocation& where) {
    if (!(light.power > 0)) return light.radiance;
    // pbrt-v4's DiffuseAreaLight::Create: Φ / (sides · π · area) for an RGB L
    // taken as one nit.
    const double sides = light.twoSided ? 2 : 1;
    if (shapeArea > 0)
        return light.radiance * float(double(light.power) / (sides * kPi * shapeArea));
    // Each primitive is its own light there, so the primitives must have one
    // area for one radiance to give each its power.
    const size_t triangles = mesh.triangleCount();
    if (primitives == 0 || triangles == 0 || triangles % primitives != 0) {
        st.unsupported(where, "area light power on this shape", "the radiance as given");
        return light.radiance;
    }
    const size_t per = triangles / primitives;
    std::vector<double> area(primitives, 0.0);
    for (size_t t = 0; t < triangles; ++t) {
        const auto P = [&](int k) { return mesh.positions[mesh.indices[3 * t + size_t(k)]]; };
        area[t / per] += 0.5 * double(length(triangleNormalArea(P(0), P(1), P(2))));
    }
    const auto [smallest, largest] = std::minmax_element(area.begin(), area.end());
    if (!(*smallest > 0) || *largest > *smallest * (1 + 1e-3)) {
        st.unsupported(where, "area light power on a shape whose parts differ in area",
                       "the radiance as given");
        return light.radiance;
    }
    return light.radiance * float(double(light.power) / (sides * kPi * *largest));
}

void lightSource(ImportState& st, const std::string& type, const ParamSet& given,
                 const SourceLocation& where) {
    const ParamSet ps = given.withDefaults(st.gs.attributes["light"]);
    if (type == "infinite") return infiniteLight(st, ps, where);
    PunctualLight light;
    if (type == "point") {
        light = pointLight(st, ps, where);
    } else if (type == "spot") {
        light = spotLight(st, ps, where);
    } else if (type == "distant") {
        light = distantLight(st, ps, where);
    } else if (type == "goniometric" || type == "projection") {
        st.unsupported(where, "LightSource '" + type + "'", "no light");
        markAllUsed(ps);
        return;
    } else {
        throw errorAt(where, "unknown light '" + type +
                                 "' (pbrt-v4 has point, spot, distant, goniometric, projection, "
                                 "infinite)");
    }
    st.checkUnused(ps, "LightSource \"" + type + "\"");
    if (st.currentObject >= 0) {
        st.unsupported(where, "a light inside ObjectBegin", "no light");
        return;
    }
    st.result.scene.punctualLights.push_back(light);
}

}  // namespace pathlab::pbrt
