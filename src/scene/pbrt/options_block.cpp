// The directives before WorldBegin: Camera, Film, PixelFilter, Sampler,
// Integrator (pbrt-v4 File Format, "Scene-wide rendering options"), and the
// importer's shared bookkeeping.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "scene/pbrt/parser_state.h"

namespace pathlab::pbrt {
namespace fs = std::filesystem;

ImportState::ImportState(const ImportOptions& options, std::string dir)
    : mainDir(std::move(dir)), options_(options) {
    // pbrt-v4's defaults where a file is silent: Gaussian filter, zsobol with
    // 16 samples, path depth 5, a 1280×720 film, a 90° perspective camera.
    SceneDescription& s = result.scene;
    s.resolution = {1280, 720};
    s.film.filter.type = FilterType::Gaussian;
    s.film.filter.radius = {1.5f, 1.5f};
    s.film.filter.sigma = 0.5f;
    s.defaults.sampler = "zsobol";
    s.defaults.samplesPerPixel = 16;
    s.defaults.maxDepth = 5;
    s.camera.pbrtFrame = true;
    s.camera.fov = 90;
}

void ImportState::unsupported(const SourceLocation& where, const std::string& what,
                              const std::string& instead) {
    if (!options_.lenient)
        throw errorAt(where, what + " is not supported (--lenient substitutes " + instead + ")");
    result.warnings.push_back(where.str() + ": warning: " + what + " is not supported; " + instead +
                              " instead");
}

void ImportState::note(const SourceLocation& where, const std::string& what) {
    result.notes.push_back(where.str() + ": note: " + what);
}

void ImportState::checkUnused(const ParamSet& params, const std::string& directive) {
    for (const Param* p : params.unused())
        unsupported(p->where,
                    "parameter \"" + std::string(paramTypeName(p->type)) + " " + p->name +
                        "\" of " + directive,
                    "nothing (it is ignored)");
}

std::string ImportState::resolveFile(const std::string& name, const std::string& includingDir,
                                     const SourceLocation& where) const {
    std::error_code ec;
    if (fs::path(name).is_absolute()) {
        if (!fs::exists(name, ec)) throw errorAt(where, "file '" + name + "' does not exist");
        return name;
    }
    for (const std::string& dir : {mainDir, includingDir}) {
        const fs::path p = fs::path(dir) / name;
        if (fs::exists(p, ec)) return p.string();
    }
    throw errorAt(where, "file '" + name + "' does not exist (looked in '" + mainDir + "'" +
                             (includingDir != mainDir ? " and '" + includingDir + "'" : "") + ")");
}

void ImportState::addTriangles(size_t count, const SourceLocation& where, bool keep) {
    if (count > options_.maxTriangles - std::min(triangles_, options_.maxTriangles))
        throw errorAt(where, "the scene has more than " + std::to_string(options_.maxTriangles) +
                                 " triangles");
    if (keep) triangles_ += count;
}

int ImportState::defaultMaterial() {
    if (defaultMaterial_ < 0) {
        Material m;
        m.name = "pbrt-default";
        m.type = MaterialType::Diffuse;
        m.albedo = Vec3f(0.5f);
        defaultMaterial_ = int(result.scene.materials.size());
        result.scene.materials.push_back(m);
    }
    return defaultMaterial_;
}

namespace {

// An array of exactly n floats, or nothing.
bool floatArray(const ParamSet& ps, const std::string& name, size_t n, float* out) {
    const std::vector<float> v = ps.getFloats(name);
    if (v.empty()) return false;
    if (v.size() != n)
        throw errorAt(ps.find(name)->where, "parameter '" + name + "' needs " + std::to_string(n) +
                                                " values, got " + std::to_string(v.size()));
    for (size_t i = 0; i < n; ++i) out[i] = v[i];
    return true;
}

}  // namespace

void camera(ImportState& st, const std::string& type, const ParamSet& ps,
            const SourceLocation& where) {
    Camera& c = st.result.scene.camera;
    if (type == "perspective") {
        c.projection = Projection::Perspective;
        c.fov = ps.getFloat("fov", 90);
        if (!(c.fov > 0 && c.fov < 180))
            throw errorAt(where, "perspective camera: fov must be in (0, 180) degrees");
    } else if (type == "orthographic") {
        c.projection = Projection::Orthographic;
    } else {
        st.unsupported(where, "camera '" + type + "'", "a perspective camera");
        c.projection = Projection::Perspective;
        c.fov = 90;
    }
    c.lensRadius = ps.getFloat("lensradius", 0);
    c.focalDistance = ps.getFloat("focaldistance", 1e6f);
    if (c.lensRadius < 0 || !(c.focalDistance > 0))
        throw errorAt(where, "camera: lensradius must be >= 0 and focaldistance > 0");
    c.frameAspectRatio = ps.getFloat("frameaspectratio", 0);
    if (floatArray(ps, "screenwindow", 4, c.screenWindow) &&
        !(c.screenWindow[0] < c.screenWindow[1] && c.screenWindow[2] < c.screenWindow[3]))
        throw errorAt(where, "camera: screenwindow must be [xmin xmax ymin ymax] with min < max");
    // pbrt-v4's imaging ratio scales the image by the shutter's open time.
    const float open = ps.getFloat("shutteropen", 0), close = ps.getFloat("shutterclose", 1);
    if (!(close >= open)) throw errorAt(where, "camera: shutterclose is before shutteropen");
    st.shutterTime = close - open;
    st.checkUnused(ps, "Camera \"" + type + "\"");
}

void film(ImportState& st, const std::string& type, const ParamSet& ps,
          const SourceLocation& where) {
    if (type == "spectral")
        st.unsupported(where, "Film \"spectral\"", "an RGB film");
    else if (type != "rgb" && type != "gbuffer")
        throw errorAt(where, "unknown film type '" + type + "' (rgb, gbuffer or spectral)");
    SceneDescription& s = st.result.scene;
    s.resolution = {ps.getInt("xresolution", 1280), ps.getInt("yresolution", 720)};
    if (s.resolution.x < 1 || s.resolution.y < 1 || s.resolution.x > 16384 ||
        s.resolution.y > 16384)
        throw errorAt(where, "Film: resolution must be between 1x1 and 16384x16384, got " +
                                 std::to_string(s.resolution.x) + "x" +
                                 std::to_string(s.resolution.y));
    float* crop = s.film.cropWindow;
    crop[0] = 0, crop[1] = 1, crop[2] = 0, crop[3] = 1;  // a later Film replaces an earlier one
    if (floatArray(ps, "cropwindow", 4, crop) &&
        !(crop[0] >= 0 && crop[0] < crop[1] && crop[1] <= 1 && crop[2] >= 0 && crop[2] < crop[3] &&
          crop[3] <= 1))
        throw errorAt(where, "Film: cropwindow must be [x0 x1 y0 y1] within [0, 1], min < max");
    const float iso = ps.getFloat("iso", 100);
    if (!(iso > 0)) throw errorAt(where, "Film: iso must be positive");
    st.isoScale = iso / 100;
    s.film.whiteBalance = ps.getFloat("whitebalance", 0);
    if (!(s.film.whiteBalance >= 0 && std::isfinite(s.film.whiteBalance)))
        throw errorAt(where, "Film: whitebalance must be 0 (none) or a temperature in kelvin");
    const std::string sensor = ps.getString("sensor", "cie1931");
    if (sensor != "cie1931") {
        // pbrt-v4's camera sensors are measured response curves (its
        // "<name>_r/_g/_b" named spectra) that pathlab does not ship.
        st.unsupported(where,
                       "Film sensor \"" + sensor +
                           "\" (pbrt-v4's measured camera curves are data pathlab does not have)",
                       "the CIE 1931 observer");
    }
    if (std::isfinite(ps.getFloat("maxcomponentvalue", INFINITY)))
        st.unsupported(where, "Film maxcomponentvalue (clamping)", "no clamping");
    for (const char* ignored : {"filename", "diagonal", "savefp16", "writefp16"})
        ps.ignore(ignored);
    if (ps.find("pixelbounds")) st.unsupported(where, "Film pixelbounds", "the full image");
    st.checkUnused(ps, "Film \"" + type + "\"");
}

void pixelFilter(ImportState& st, const std::string& type, const ParamSet& ps,
                 const SourceLocation& where) {
    PixelFilter& f = st.result.scene.film.filter;
    f = PixelFilter{};
    float radius = 0;
    if (type == "box") {
        f.type = FilterType::Box, radius = 0.5f;
    } else if (type == "gaussian") {
        f.type = FilterType::Gaussian, radius = 1.5f;
        f.sigma = ps.getFloat("sigma", 0.5f);
    } else if (type == "triangle") {
        f.type = FilterType::Triangle, radius = 2;
    } else if (type == "mitchell") {
        f.type = FilterType::Mitchell, radius = 2;
        f.b = ps.getFloat("B", 1 / 3.0f);
        f.c = ps.getFloat("C", 1 / 3.0f);
    } else if (type == "sinc") {
        f.type = FilterType::Lanczos, radius = 4;
        f.tau = ps.getFloat("tau", 3);
    } else {
        throw errorAt(
            where, "unknown pixel filter '" + type + "' (box, gaussian, triangle, mitchell, sinc)");
    }
    f.radius = {ps.getFloat("xradius", radius), ps.getFloat("yradius", radius)};
    if (!(f.radius.x > 0 && f.radius.y > 0 && f.radius.x <= 16 && f.radius.y <= 16))
        throw errorAt(where, "PixelFilter: radii must be in (0, 16]");
    if (f.type == FilterType::Gaussian && !(f.sigma > 0))
        throw errorAt(where, "PixelFilter: sigma must be positive");
    st.checkUnused(ps, "PixelFilter \"" + type + "\"");
}

// pbrt-v4's samplers (samplers.cpp, each Create) by family and randomization.
// A combination pathlab has no sampler for is unsupported, not silently
// swapped: a sampler study must know what it measured.
void sampler(ImportState& st, const std::string& type, const ParamSet& ps,
             const SourceLocation& where) {
    RenderDefaults& d = st.result.scene.defaults;
    const bool scrambles =
        type == "halton" || type == "sobol" || type == "paddedsobol" || type == "zsobol";
    const std::string r = scrambles ? ps.getString("randomization", "") : "";
    if (!r.empty() && r != "none" && r != "permutedigits" && r != "owen" && r != "fastowen")
        throw errorAt(ps.find("randomization")->where,
                      "randomization must be none, permutedigits, owen or fastowen");
    std::string ours;
    const auto nearest = [&](const std::string& what, const std::string& instead) {
        st.unsupported(where, what, instead);
        return instead;
    };
    if (type == "independent") {
        ours = "independent";
    } else if (type == "stratified") {
        ours = "stratified";
        if (!ps.getBool("jitter", true))
            st.unsupported(where, "stratified sampling without jitter", "jittered strata");
        const int64_t xs = ps.getInt("xsamples", 4), ys = ps.getInt("ysamples", 4);
        if (xs < 1 || ys < 1 || xs * ys > (1 << 24))
            throw errorAt(where, "Sampler: xsamples × ysamples must be between 1 and 16777216");
        d.samplesPerPixel = int(xs * ys);
    } else if (type == "halton") {
        if (r == "fastowen")
            throw errorAt(where,
                          "halton does not take randomization \"fastowen\" (pbrt-v4 "
                          "neither)");
        ours = r == "none" ? "halton" : r == "owen" ? "halton-owen" : "halton-rd";
    } else if (type == "sobol") {
        ours = r == "none" ? "sobol" : r == "permutedigits" ? "sobol-xor" : "sobol-global-owen";
    } else if (type == "paddedsobol") {
        ours = r == "" || r == "owen" || r == "fastowen"
                   ? "sobol-owen"
                   : nearest("paddedsobol with randomization '" + r + "'", "sobol-owen");
    } else if (type == "zsobol") {
        ours = r == "" || r == "owen" || r == "fastowen"
                   ? "zsobol"
                   : nearest("zsobol with randomization '" + r + "'", "zsobol");
    } else if (type == "pmj02bn") {
        ours = "pmj02";
    } else {
        throw errorAt(where, "unknown sampler '" + type +
                                 "' (independent, stratified, halton, sobol, paddedsobol, zsobol, "
                                 "pmj02bn)");
    }
    d.sampler = ours;
    // pbrt-v4's IndependentSampler takes 4 samples unless told; the others 16.
    if (type != "stratified")
        d.samplesPerPixel = ps.getInt("pixelsamples", type == "independent" ? 4 : 16);
    if (d.samplesPerPixel < 1 || d.samplesPerPixel > (1 << 24))
        throw errorAt(where, "Sampler: pixelsamples must be between 1 and 16777216");
    d.hasSeed = false;
    if (ps.find("seed")) {
        const int seed = ps.getInt("seed", 0);
        if (seed < 0) throw errorAt(where, "Sampler: seed must not be negative");
        d.hasSeed = true;
        d.seed = uint64_t(seed);
    }
    st.checkUnused(ps, "Sampler \"" + type + "\"");
}

void integrator(ImportState& st, const std::string& type, const ParamSet& ps,
                const SourceLocation& where) {
    if (type != "path" && type != "volpath")
        throw errorAt(where, "integrator '" + type +
                                 "' is not supported (pathlab renders with a path tracer: use "
                                 "\"path\" or \"volpath\")");
    const int depth = ps.getInt("maxdepth", 5);
    if (depth < 0 || depth > 1024)
        throw errorAt(where, "Integrator: maxdepth must be in [0, 1024]");
    st.result.scene.defaults.maxDepth = depth;
    if (ps.getBool("regularize", false))
        st.note(where, "Integrator regularize ignored: pathlab does not regularize BSDFs");
    if (ps.find("lightsampler"))
        st.note(where, "Integrator lightsampler ignored: pathlab chooses lights its own way");
    st.checkUnused(ps, "Integrator \"" + type + "\"");
}

}  // namespace pathlab::pbrt

namespace pathlab::pbrt {

// At WorldBegin: the camera's frame from the CTM its directive saw. Where the
// camera is a pinhole whose frame is what pathlab's own eye/target/up camera
// builds (unit orthogonal axes, image right = forward × up, the default
// screen window), it is stored in that form, so that such a file renders
// exactly as the same camera written in pathlab's JSON (scenes/cornell-box.pbrt
// and the built-in cornell-box, bit for bit).
void finishOptions(ImportState& st) {
    // pbrt-v4's imaging ratio: exposure time × ISO / 100.
    st.result.scene.film.scale = st.shutterTime * st.isoScale;
    Camera& c = st.result.scene.camera;
    const auto worldFromCamera = st.cameraFromWorld.inverse();
    if (!worldFromCamera || !worldFromCamera->isAffine())
        throw errorAt(st.cameraWhere,
                      "the camera transform is singular or projective (check the transforms "
                      "before Camera)");
    c.eye = worldFromCamera->point({0, 0, 0});
    c.axisX = worldFromCamera->vector({1, 0, 0});
    c.axisY = worldFromCamera->vector({0, 1, 0});
    c.axisZ = worldFromCamera->vector({0, 0, 1});
    const auto unit = [](Vec3f v) { return std::abs(length(v) - 1) < 1e-6f; };
    const bool orthonormal = unit(c.axisX) && unit(c.axisY) && unit(c.axisZ) &&
                             std::abs(dot(c.axisX, c.axisY)) < 1e-6f &&
                             std::abs(dot(c.axisX, c.axisZ)) < 1e-6f &&
                             std::abs(dot(c.axisY, c.axisZ)) < 1e-6f;
    const bool defaultWindow = c.screenWindow[0] == 0 && c.screenWindow[1] == 0 &&
                               c.screenWindow[2] == 0 && c.screenWindow[3] == 0;
    const Vec2i res = st.result.scene.resolution;
    const float aspect = float(res.x) / float(res.y);
    const bool sameAspect = c.frameAspectRatio == 0 || c.frameAspectRatio == aspect;
    const float crop[4] = {0, 1, 0, 1};
    const bool uncropped = std::equal(crop, crop + 4, st.result.scene.film.cropWindow);
    if (c.projection == Projection::Perspective && c.lensRadius == 0 && orthonormal &&
        defaultWindow && sameAspect && uncropped &&
        length(c.axisX - cross(c.axisZ, c.axisY)) < 1e-6f) {
        c.pbrtFrame = false;
        c.target = c.eye + c.axisZ;
        c.up = c.axisY;
        // pbrt-v4's fov spans the shorter side; pathlab's fovY the vertical.
        const double tanHalf = std::tan(double(c.fov) * 3.14159265358979323846 / 360);
        c.fovY = aspect >= 1
                     ? c.fov
                     : float(2 * std::atan(tanHalf / aspect) * 180 / 3.14159265358979323846);
    }
}

}  // namespace pathlab::pbrt
