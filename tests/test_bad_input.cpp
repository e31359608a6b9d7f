// Bad input, command by command — the table in the README's "Bad input"
// section. Each case must give exit code 2 and one line on stderr naming the
// problem, create no output, and leave an output already there unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

#include "cli_runner.h"
#include "core/image.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;

struct BadInput {
    const char* input;    // what is wrong, as in the README's table
    const char* args;     // {dir} is the scratch directory
    const char* output;   // what the command would write ("" when nothing)
    const char* message;  // the one line after "pathlab: error: ", {dir} as above
};

// The README's table, row for row.
const BadInput kCases[] = {
    {"missing scene file", "render --scene {dir}/missing.json -o {dir}/out.png", "out.png",
     "unknown scene '{dir}/missing.json': neither a built-in scene (cornell-box, wolf) nor an "
     "existing file"},
    {"malformed JSON scene", "render --scene {dir}/broken.json -o {dir}/out.png", "out.png",
     "{dir}/broken.json: invalid JSON: parse error at line 1, column 29: syntax error while "
     "parsing value - unexpected end of input; expected '[', '{', or a literal"},
    {"OBJ with a bad index", "render --scene {dir}/bad-index.obj -o {dir}/out.png", "out.png",
     "OBJ file '{dir}/bad-index.obj': face 0 of '' has an index out of range (3 vertices)"},
    {"OBJ with a NaN vertex", "render --scene {dir}/nan.obj -o {dir}/out.png", "out.png",
     "OBJ file '{dir}/nan.obj' line 2: vertex coordinate 'nan' is not a finite number"},
    {"zero-area light", "render --scene {dir}/flat-lamp.obj -o {dir}/out.png", "out.png",
     "{dir}/flat-lamp.obj: light mesh 'flat-lamp/lamp' has a zero-area triangle 1"},
    {"unknown scene", "render --scene nowhere -o {dir}/out.png", "out.png",
     "unknown scene 'nowhere': neither a built-in scene (cornell-box, wolf) nor an existing file"},
    {"unknown sampler", "render --scene cornell-box --sampler nonsense -o {dir}/out.png", "out.png",
     "SAMPLER"},
    {"zero spp", "render --scene cornell-box --spp 0 -o {dir}/out.png", "out.png",
     "--spp must be between 1 and 16777216, got 0"},
    {"negative spp", "render --scene cornell-box --spp -5 -o {dir}/out.png", "out.png",
     "--spp must be between 1 and 16777216, got -5"},
    {"absurd spp", "render --scene cornell-box --spp 1000000000000 -o {dir}/out.png", "out.png",
     "--spp must be between 1 and 16777216, got 1000000000000"},
    {"zero size", "render --scene cornell-box --size 0x0 -o {dir}/out.png", "out.png",
     "--size must be between 1x1 and 16384x16384, got '0x0'"},
    {"absurd size", "render --scene cornell-box --size 1000000x1000000 -o {dir}/out.png", "out.png",
     "--size must be between 1x1 and 16384x16384, got '1000000x1000000'"},
    {"size that is no size", "render --scene cornell-box --size huge -o {dir}/out.png", "out.png",
     "--size must look like WIDTHxHEIGHT (e.g. 512x512), got 'huge'"},
    {"negative depth", "render --scene cornell-box --max-depth -3 -o {dir}/out.png", "out.png",
     "--max-depth must be between 0 and 1024, got -3"},
    {"absurd depth", "render --scene cornell-box --max-depth 100000000000 -o {dir}/out.png",
     "out.png", "--max-depth must be between 0 and 1024, got 100000000000"},
    {"unknown light sampler", "render --scene cornell-box --light-sampler tree -o {dir}/out.png",
     "out.png", "--light-sampler must be one of uniform, power, bvh, got 'tree'"},
    {"negative threads", "render --scene cornell-box --threads -1 -o {dir}/out.png", "out.png",
     "threads must be between 0 (all cores) and 4096, got -1"},
    {"negative seed", "render --scene cornell-box --seed -1 -o {dir}/out.png", "out.png",
     "--seed must be an integer between 0 and 18446744073709551615, got '-1'"},
    {"absurd seed", "render --scene cornell-box --seed 99999999999999999999 -o {dir}/out.png",
     "out.png",
     "--seed must be an integer between 0 and 18446744073709551615, got '99999999999999999999'"},
    {"absurd size in a scene", "render --scene {dir}/huge-size.json -o {dir}/out.png", "out.png",
     "{dir}/huge-size.json: resolution[0]: must be between 1 and 16384, got 65536"},
    {"scene mesh from an empty OBJ", "render --scene {dir}/empty-obj.json -o {dir}/out.png",
     "out.png", "{dir}/empty-obj.json: meshes[0].obj: OBJ file '{dir}/empty.obj' has no faces"},
    {"scene mesh from a file that is no OBJ",
     "render --scene {dir}/garbage-obj.json -o {dir}/out.png", "out.png",
     "{dir}/garbage-obj.json: meshes[0].obj: OBJ file '{dir}/garbage.obj' has no faces"},
    {"scene mesh from a missing OBJ", "render --scene {dir}/missing-obj.json -o {dir}/out.png",
     "out.png", "{dir}/missing-obj.json: meshes[0].obj: file '{dir}/missing.obj' does not exist"},
    {"scene mesh from a directory", "render --scene {dir}/dir-obj.json -o {dir}/out.png", "out.png",
     "{dir}/dir-obj.json: meshes[0].obj: '{dir}/objdir' is not a regular file"},
    {"texture with a NaN texel", "render --scene {dir}/nan-texture.json -o {dir}/out.png",
     "out.png",
     "{dir}/nan-texture.json: materials.m.texture: texture '{dir}/nan-texel.pfm' has a NaN or "
     "infinite texel at (1, 0)"},
    {"texture with a negative texel", "render --scene {dir}/negative-texture.json -o {dir}/out.png",
     "out.png",
     "{dir}/negative-texture.json: materials.m.texture: texture '{dir}/negative-texel.pfm' has a "
     "negative texel at (2, 1)"},
    {"pbrt: unknown directive", "render --scene {dir}/unknown-directive.pbrt -o {dir}/out.png",
     "out.png", "{dir}/unknown-directive.pbrt:2:1: unknown directive 'Shpe'"},
    {"pbrt: unterminated string", "render --scene {dir}/unterminated.pbrt -o {dir}/out.png",
     "out.png", "{dir}/unterminated.pbrt:2:7: unterminated string"},
    {"pbrt: wrong parameter type", "render --scene {dir}/wrong-type.pbrt -o {dir}/out.png",
     "out.png", "{dir}/wrong-type.pbrt:1:22: parameter 'fov' must be of type float, not string"},
    {"pbrt: missing Include", "render --scene {dir}/missing-include.pbrt -o {dir}/out.png",
     "out.png", "{dir}/missing-include.pbrt:2:1: file '{dir}/nothere.pbrt' does not exist"},
    {"pbrt: missing PLY", "render --scene {dir}/missing-ply.pbrt -o {dir}/out.png", "out.png",
     "{dir}/missing-ply.pbrt:2:1: file 'nothere.ply' does not exist (looked in '{dir}')"},
    {"pbrt: missing normal map", "render --scene {dir}/missing-normalmap.pbrt -o {dir}/out.png",
     "out.png",
     "{dir}/missing-normalmap.pbrt:2:20: file 'nothere.png' does not exist (looked in '{dir}')"},
    {"missing bump map", "render --scene {dir}/missing-bumpmap.json -o {dir}/out.png", "out.png",
     "{dir}/missing-bumpmap.json: materials.m.bumpMap: file '{dir}/nothere.png' does not exist"},
    {"pbrt: truncated PLY", "render --scene {dir}/truncated-ply.pbrt -o {dir}/out.png", "out.png",
     "TRUNCATED-PLY"},
    {"pbrt: index out of range", "render --scene {dir}/bad-index.pbrt -o {dir}/out.png", "out.png",
     "{dir}/bad-index.pbrt:2:1: trianglemesh: index 7 (entry 2) is out of range (3 vertices)"},
    {"pbrt: undefined named material", "render --scene {dir}/no-material.pbrt -o {dir}/out.png",
     "out.png", "{dir}/no-material.pbrt:2:1: NamedMaterial: no material named 'gold'"},
    {"pbrt: mix of a material not yet defined",
     "render --scene {dir}/mix-undefined.pbrt -o {dir}/out.png", "out.png",
     "{dir}/mix-undefined.pbrt:2:1: mix: no material named 'gold' defined before it"},
    {"pbrt: named material defined twice", "render --scene {dir}/redefined.pbrt -o {dir}/out.png",
     "out.png", "{dir}/redefined.pbrt:3:1: MakeNamedMaterial: material 'm' is already defined"},
    {"mix material containing itself", "render --scene {dir}/mix-cycle.json -o {dir}/out.png",
     "out.png", "{dir}/mix-cycle.json: materials: mix material 'a' contains itself"},
    {"pbrt: undefined object", "render --scene {dir}/no-object.pbrt -o {dir}/out.png", "out.png",
     "{dir}/no-object.pbrt:2:1: ObjectInstance: no object named 'tree'"},
    {"pbrt: undefined coordinate system", "render --scene {dir}/no-coordsys.pbrt -o {dir}/out.png",
     "out.png", "{dir}/no-coordsys.pbrt:2:1: CoordSysTransform: no coordinate system named 'lamp'"},
    {"pbrt: unbalanced AttributeEnd", "render --scene {dir}/unbalanced.pbrt -o {dir}/out.png",
     "out.png", "{dir}/unbalanced.pbrt:2:1: unbalanced AttributeEnd: no AttributeBegin is open"},
    {"pbrt: spot light cone out of range", "render --scene {dir}/wide-spot.pbrt -o {dir}/out.png",
     "out.png",
     "{dir}/wide-spot.pbrt:2:1: LightSource \"spot\": coneangle must be in (0, 180] degrees"},
    {"pbrt: negative point light", "render --scene {dir}/negative-point.pbrt -o {dir}/out.png",
     "out.png", "{dir}/negative-point.pbrt:2:1: LightSource \"point\": I must not be negative"},
    {"pbrt: distant light from = to", "render --scene {dir}/still-sun.pbrt -o {dir}/out.png",
     "out.png",
     "{dir}/still-sun.pbrt:2:1: LightSource \"distant\": 'from' and 'to' must be different "
     "points"},
    {"pbrt: environment map not square", "render --scene {dir}/wide-sky.pbrt -o {dir}/out.png",
     "out.png",
     "{dir}/wide-sky.pbrt:2:1: LightSource \"infinite\": 'wide-sky.pfm' is 4x2, not square: not "
     "an equal-area octahedral map"},
    {"pbrt: unknown light", "render --scene {dir}/unknown-light.pbrt -o {dir}/out.png", "out.png",
     "{dir}/unknown-light.pbrt:2:1: unknown light 'lamp' (pbrt-v4 has point, spot, distant, "
     "goniometric, projection, infinite)"},
    {"spot light with a negative delta", "render --scene {dir}/bad-spot.json -o {dir}/out.png",
     "out.png",
     "{dir}/bad-spot.json: lights[0].coneDeltaAngle: coneDeltaAngle must be in [0, coneAngle]"},
    {"distant light without direction", "render --scene {dir}/bad-sun.json -o {dir}/out.png",
     "out.png", "{dir}/bad-sun.json: lights[0].direction: a direction must not be zero"},
    {"pbrt: unsupported feature", "render --scene {dir}/unsupported.pbrt -o {dir}/out.png",
     "out.png",
     "{dir}/unsupported.pbrt:2:1: material 'hair' (or these parameters of it) is not "
     "supported (--lenient substitutes diffuse grey)"},
    {"output directory missing", "render --scene cornell-box -o {dir}/no/such/out.png", "",
     "cannot write '{dir}/no/such/out.png': directory '{dir}/no/such' does not exist"},
    {"output under a file", "render --scene cornell-box -o {dir}/a.exr/out.png", "",
     "cannot write '{dir}/a.exr/out.png': '{dir}/a.exr' is not a directory"},
    {"unknown output type", "render --scene cornell-box -o {dir}/out.tiff", "out.tiff",
     "unsupported image type '.tiff' for '{dir}/out.tiff' (expected .exr, .png or .pfm)"},
    {"unknown option", "render --scene cornell-box --frobnicate -o {dir}/out.png", "out.png",
     "The following argument was not expected: --frobnicate"},
    {"unknown command", "frobnicate {dir}/a.exr", "",
     "unknown command 'frobnicate' (commands: render, compare, samplers, points, study, bench, "
     "report, view)"},
    {"images of different sizes", "compare {dir}/a.exr {dir}/small.exr --error-map {dir}/map.png",
     "map.png", "SIZES"},
    {"NaN pixels", "compare {dir}/a.exr {dir}/nan.exr --error-map {dir}/map.png", "map.png", "NAN"},
    {"missing image", "compare {dir}/a.exr {dir}/missing.exr --error-map {dir}/map.png", "map.png",
     "image '{dir}/missing.exr' does not exist or is not a file"},
    {"not an image", "compare {dir}/a.exr {dir}/junk.exr --error-map {dir}/map.png", "map.png",
     "JUNK"},
    {"image header claiming an absurd size",
     "compare {dir}/a.exr {dir}/huge.pfm --error-map {dir}/map.png", "map.png",
     "image '{dir}/huge.pfm' is 100000x100000, larger than the 16384x16384 pathlab reads"},
    {"truncated image", "compare {dir}/a.exr {dir}/truncated.pfm --error-map {dir}/map.png",
     "map.png", "'{dir}/truncated.pfm' is truncated"},
    {"unknown metric", "compare {dir}/a.exr {dir}/a.exr --metric ssim", "",
     "--metric: ssim not in {mse,rmse,relmse,psnr,bias,flip,all}"},
    {"absurd pixels per degree",
     "compare {dir}/a.exr {dir}/a.exr --ppd 1e30 --error-map {dir}/map.png", "map.png",
     "--ppd must be a number of pixels per degree between 1 and 1000, got '1e30'"},
    {"NaN pixels per degree", "compare {dir}/a.exr {dir}/a.exr --ppd nan --error-map {dir}/map.png",
     "map.png", "--ppd must be a number of pixels per degree between 1 and 1000, got 'nan'"},
    {"zero pixels per degree", "compare {dir}/a.exr {dir}/a.exr --ppd 0 --error-map {dir}/map.png",
     "map.png", "--ppd must be a number of pixels per degree between 1 and 1000, got '0'"},
    {"pixels per degree that are no number",
     "compare {dir}/a.exr {dir}/a.exr --ppd abc --error-map {dir}/map.png", "map.png",
     "--ppd must be a number of pixels per degree between 1 and 1000, got 'abc'"},
    {"error spectrum of an unknown type",
     "compare {dir}/a.exr {dir}/a.exr --error-spectrum {dir}/spectrum.txt", "spectrum.txt",
     "--error-spectrum must name a .csv or .png file, got '{dir}/spectrum.txt'"},
    {"error spectrum in a missing directory",
     "compare {dir}/a.exr {dir}/a.exr --error-spectrum {dir}/no/such/spectrum.csv", "",
     "cannot write '{dir}/no/such/spectrum.csv': directory '{dir}/no/such' does not exist"},
    {"points: pixel beyond any image",
     "points --sampler sobol --count 4 --dims 0,1 --pixel 9999999,9999999 -o {dir}/pts.csv",
     "pts.csv", "--pixel must lie in an image between 1x1 and 16384x16384, got '9999999,9999999'"},
    {"points: absurd spp",
     "points --sampler pmj02 --count 4 --dims 0,1 --spp 2000000000 -o {dir}/pts.csv", "pts.csv",
     "--spp must be between 1 and 16777216, got 2000000000"},
    {"points: zero spp", "points --sampler pmj02 --count 4 --dims 0,1 --spp 0 -o {dir}/pts.csv",
     "pts.csv", "--spp must be between 1 and 16777216, got 0"},
    {"points: zero resolution",
     "points --sampler sobol --count 4 --dims 0,1 --resolution 0x0 -o {dir}/pts.csv", "pts.csv",
     "--resolution must be between 1x1 and 16384x16384, got '0x0'"},
    {"points: one dimension twice", "points --sampler sobol --count 4 --dims 1,1 -o {dir}/pts.csv",
     "pts.csv", "--dims must name two different dimensions, got '1,1'"},
    {"points: negative seed",
     "points --sampler sobol --count 4 --dims 0,1 --seed -1 -o {dir}/pts.csv", "pts.csv",
     "--seed must be an integer between 0 and 18446744073709551615, got '-1'"},
    {"missing study spec", "study {dir}/missing.toml -o {dir}/study", "study",
     "study spec '{dir}/missing.toml' does not exist or is not a file"},
    {"malformed TOML spec", "study {dir}/broken.toml -o {dir}/study", "study",
     "{dir}/broken.toml:4:1: not valid TOML: Error while parsing array: expected comma or "
     "closing ']', saw 's'"},
    {"unknown key in spec", "study {dir}/unknown-key.toml -o {dir}/study", "study",
     "{dir}/unknown-key.toml:4: key 'seedz' is not a study spec key (known: name, scenes, "
     "samplers, spp, seeds, resolution, max_depth, russian_roulette, "
     "roulette_depth, light_sampler, spectral, wavelengths, metrics, time_budget_seconds, "
     "reference, "
     "external, "
     "difficulty)"},
    {"unknown sampler in spec", "study {dir}/unknown-sampler.toml -o {dir}/study", "study",
     "SPEC-SAMPLER"},
    {"absurd spp in spec", "study {dir}/absurd-spp.toml -o {dir}/study", "study",
     "{dir}/absurd-spp.toml:3: key 'spp[0]' must be between 1 and 16777216, got 1000000000000"},
    {"absurd size in spec", "study {dir}/absurd-size.toml -o {dir}/study", "study",
     "{dir}/absurd-size.toml:4: key 'resolution[0]' must be between 1 and 16384, got 1000000"},
    {"unknown preset", "study --preset nope -o {dir}/study", "study",
     "unknown preset 'nope' (known: seed, quick, full, suite, quick-suite)"},
    {"scenes dir that is no directory",
     "study --preset quick-suite --scenes-dir {dir}/nowhere -o {dir}/study", "study",
     "--scenes-dir '{dir}/nowhere' is not a directory"},
    {"absurd study threads", "study {dir}/ok.toml -o {dir}/study --threads 5000", "study",
     "--threads must be between 0 (all cores) and 4096, got 5000"},
    {"a spec's scene that cannot be loaded", "study {dir}/bad-scene.toml -o {dir}/study", "study",
     "{dir}/bad-scene.toml:1: key 'scenes[0]' names a scene that cannot be loaded: "
     "{dir}/bad-fov.json: camera.fovY: must be in (0, 180) degrees"},
    {"study directory that is a file", "study {dir}/ok.toml -o {dir}/a.exr", "",
     "'{dir}/a.exr' is not a directory: -o/--output must name the study directory"},
    {"study directory in use", "study --preset quick -o {dir}/used", "",
     "'{dir}/used' is not empty: add --resume to continue the study in it, or choose another "
     "directory"},
    {"another study's directory", "study {dir}/ok.toml -o {dir}/other --resume", "",
     "'{dir}/other' holds a study whose 'max_depth' differs from this spec: choose another "
     "directory"},
    {"no study to report", "report {dir}/used", "",
     "'{dir}/used' is not a study directory (no "
     "results.sqlite)"},
    {"bench of an unknown scene", "bench --scene nope --no-scaling", "",
     "unknown scene 'nope': neither a built-in scene (cornell-box, wolf) nor an existing file"},
};

std::string substituted(std::string text, const std::string& dir) {
    for (size_t at; (at = text.find("{dir}")) != std::string::npos;) text.replace(at, 5, dir);
    return text;
}

// Names and contents of every file under `dir`.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> out;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        out[entry.path().string()] =
            entry.is_regular_file() ? testing::slurpFile(entry.path()) : "<directory>";
    return out;
}

// A valid scene with `extra` keys added, for the scene rows.
std::string sceneWith(const std::string& extra) {
    return R"({"camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
      "lights": [{"type": "quad", "vertices": [[0,3,0], [1,3,0], [1,3,1], [0,3,1]],
                  "emission": 10}])" +
           extra + "}";
}

// A 4x2 texture whose texel `texel` has `value` in its green channel.
void writeTexture(const fs::path& path, int texel, float value) {
    Image image(4, 2);
    std::fill(image.rgb.begin(), image.rgb.end(), 0.5f);
    image.rgb[size_t(3 * texel + 1)] = value;
    writeImage(path.string(), image);
}

class BadInputTable : public ::testing::Test {
  protected:
    template <typename Put>
    void putScenes(const Put& put) {
        put("huge-size.json", sceneWith(R"(, "resolution": [65536, 65536])"));
        const std::string sphere =
            R"({"camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
      "materials": {"m": {"type": "diffuse"}},
      "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "m"}], "lights": [)";
        put("bad-spot.json", sphere + R"({"type": "spot", "position": [0, 3, 0],
            "direction": [0, -1, 0], "intensity": 5, "coneAngle": 20, "coneDeltaAngle": -1}]})");
        put("bad-sun.json",
            sphere + R"({"type": "distant", "direction": [0, 0, 0], "radiance": 3}]})");
        put("empty.obj", "");
        put("garbage.obj", "this is not an OBJ file\n\x01\x02\n");
        fs::create_directory(dir / "objdir");
        for (const char* name : {"empty", "garbage", "missing"})
            put(std::string(name) + "-obj.json",
                sceneWith(R"(, "meshes": [{"obj": ")" + std::string(name) + R"(.obj"}])"));
        put("dir-obj.json", sceneWith(R"(, "meshes": [{"obj": "objdir"}])"));
        writeTexture(dir / "nan-texel.pfm", 1, std::numeric_limits<float>::quiet_NaN());
        writeTexture(dir / "negative-texel.pfm", 6, -0.25f);
        for (const char* name : {"nan", "negative"})
            put(std::string(name) + "-texture.json",
                sceneWith(R"(, "materials": {"m": {"type": "diffuse", "texture": ")" +
                          std::string(name) +
                          R"(-texel.pfm"}},
                "meshes": [{"material": "m", "quads": [[[-1,0,-1], [-1,0,1], [1,0,1], [1,0,-1]]]}])"));
        put("missing-bumpmap.json",
            sceneWith(R"(, "materials": {"m": {"type": "diffuse", "bumpMap": "nothere.png"}},
                "meshes": [{"material": "m", "quads": [[[-1,0,-1], [-1,0,1], [1,0,1], [1,0,-1]]]}])"));
        put("missing-normalmap.pbrt",
            "WorldBegin\nMaterial \"diffuse\" \"string normalmap\" \"nothere.png\"\n");
        std::string badFov = sceneWith("");
        badFov.replace(badFov.find("\"fovY\": 40"), 10, "\"fovY\": 0");
        put("bad-fov.json", badFov);
        put("bad-scene.toml", "scenes = [\"bad-fov.json\"]\nsamplers = [\"halton\"]\nspp = [1]\n");
        const std::string tri = "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]";
        put("unknown-directive.pbrt", "WorldBegin\nShpe \"sphere\"\n");
        put("unterminated.pbrt", "WorldBegin\nShape \"sphere\n");
        put("wrong-type.pbrt", "Camera \"perspective\" \"string fov\" \"wide\"\nWorldBegin\n");
        put("missing-include.pbrt", "WorldBegin\nInclude \"nothere.pbrt\"\n");
        put("missing-ply.pbrt",
            "WorldBegin\nShape \"plymesh\" \"string filename\" \"nothere.ply\"\n");
        put("truncated.ply",
            "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
            "property float y\nproperty float z\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n\x01\x02");
        put("truncated-ply.pbrt",
            "WorldBegin\nShape \"plymesh\" \"string filename\" \"truncated.ply\"\n");
        put("bad-index.pbrt", "WorldBegin\n" + tri + " \"integer indices\" [0 1 7]\n");
        put("no-material.pbrt", "WorldBegin\nNamedMaterial \"gold\"\n" + tri + "\n");
        put("mix-undefined.pbrt",
            "WorldBegin\nMaterial \"mix\" \"string materials\" [\"gold\" \"red\"]\n" + tri + "\n");
        put("redefined.pbrt",
            "WorldBegin\nMakeNamedMaterial \"m\" \"string type\" \"diffuse\"\n"
            "MakeNamedMaterial \"m\" \"string type\" \"diffuse\"\n" +
                tri + "\n");
        put("mix-cycle.json",
            sceneWith(R"(, "materials": {"a": {"type": "mix", "materials": ["b", "c"]},
                                          "b": {"type": "mix", "materials": ["a", "c"]},
                                          "c": {"type": "diffuse"}})"));
        put("no-object.pbrt", "WorldBegin\nObjectInstance \"tree\"\n");
        put("no-coordsys.pbrt", "WorldBegin\nCoordSysTransform \"lamp\"\n");
        put("unbalanced.pbrt", "WorldBegin\nAttributeEnd\n");
        put("unsupported.pbrt", "WorldBegin\nMaterial \"hair\"\n" + tri + "\n");
        put("wide-spot.pbrt", "WorldBegin\nLightSource \"spot\" \"float coneangle\" 200\n" + tri);
        put("negative-point.pbrt", "WorldBegin\nLightSource \"point\" \"rgb I\" [1 -1 1]\n" + tri);
        put("still-sun.pbrt",
            "WorldBegin\nLightSource \"distant\" \"point3 from\" [1 1 1] \"point3 to\" [1 1 1]\n" +
                tri);
        writeTexture(dir / "wide-sky.pfm", 0, 0.5f);
        put("wide-sky.pbrt",
            "WorldBegin\nLightSource \"infinite\" \"string filename\" \"wide-sky.pfm\"\n" + tri);
        put("unknown-light.pbrt", "WorldBegin\nLightSource \"lamp\"\n" + tri);
    }

    void SetUp() override {
        dir = testing::scratchDirectory("bad-input");
        const auto put = [&](const std::string& name, const std::string& text) {
            std::ofstream(dir / name, std::ios::binary) << text;
        };
        put("broken.json", "{ \"camera\": { \"eye\": [0, 0, ");
        put("bad-index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
        put("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
        put("flat-lamp.mtl", "newmtl lamp\nKe 1 1 1\n");
        put("flat-lamp.obj",
            "mtllib flat-lamp.mtl\nv 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nusemtl lamp\nf 1 2 4\n"
            "f 1 2 3\n");
        writeImage((dir / "a.exr").string(), Image(8, 8));
        writeImage((dir / "small.exr").string(), Image(8, 6));
        Image nan(8, 8);
        nan.rgb[5] = std::numeric_limits<float>::quiet_NaN();
        writeImage((dir / "nan.exr").string(), nan);
        put("junk.exr", "this is not an EXR file");
        put("huge.pfm", "PF\n100000 100000\n-1\nabcd");
        put("truncated.pfm", "PF\n100 100\n-1\nabcd");
        const std::string spec = "scenes = [\"cornell-box\"]\nsamplers = [\"halton\"]\n";
        put("broken.toml", spec + "spp = [1, 2\nseeds = 2\n");
        put("unknown-key.toml", spec + "spp = [1]\nseedz = 3\n");
        put("unknown-sampler.toml",
            "scenes = [\"cornell-box\"]\nsamplers = [\"halton\", \"nope\"]\nspp = [1]\n");
        put("absurd-spp.toml", spec + "spp = [1000000000000]\n");
        put("absurd-size.toml", spec + "spp = [1]\nresolution = [1000000, 1000000]\n");
        put("ok.toml", spec + "spp = [1]\n");
        putScenes(put);
        fs::create_directory(dir / "other");
        put("other/spec.toml", spec + "spp = [1]\nmax_depth = 3\n");
        fs::create_directory(dir / "used");
        put("used/notes.txt", "someone's work\n");
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
};

TEST_F(BadInputTable, OneLineExitCodeTwoNothingWrittenNothingLost) {
    const std::string d = dir.string();
    // The messages the placeholders stand for: they depend on a library's
    // wording or list every sampler, so only their start is pinned down.
    const std::map<std::string, std::string> prefixes = {
        {"SAMPLER", "unknown sampler 'nonsense' (known: "},
        {"SIZES", ""},
        {"NAN", ""},
        {"JUNK", "cannot read EXR '" + d + "/junk.exr': "},
        {"SPEC-SAMPLER", d + "/unknown-sampler.toml:2: key 'samplers[1]' names an unknown "
                             "sampler 'nope' (known: "},
        {"TRUNCATED-PLY", d + "/truncated-ply.pbrt:2:1: "},
    };
    const std::map<std::string, std::string> mentions = {
        {"SAMPLER", "halton"}, {"SIZES", "8x6"},         {"NAN", "NaN"},
        {"JUNK", "junk.exr"},  {"SPEC-SAMPLER", "nope"}, {"TRUNCATED-PLY", "truncated.ply"},
    };
    for (const BadInput& c : kCases) {
        SCOPED_TRACE(c.input);
        const std::string args = substituted(c.args, d);
        const std::string output = *c.output ? (dir / c.output).string() : "";
        for (const bool existing : {false, true}) {
            if (existing && output.empty()) continue;
            SCOPED_TRACE(existing ? "output already there" : "no output yet");
            if (existing) {
                if (std::string(c.args).rfind("study", 0) == 0) {
                    fs::create_directory(output);
                    std::ofstream(fs::path(output) / "earlier.txt") << "earlier work\n";
                } else {
                    std::ofstream(output) << "an earlier output\n";
                }
            }
            const auto before = snapshot(dir);
            const auto r = testing::runPathlab(args, dir);
            EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
            EXPECT_EQ(r.errLines(), 1) << args << "\n" << r.err;
            EXPECT_EQ(r.out, "") << args;  // nothing measured or printed first
            const std::string line = r.err.substr(0, r.err.find('\n'));
            if (std::getenv("PATHLAB_PRINT_BAD_INPUT") && !existing)
                std::printf("%s\t%s\t%s\n", c.input, args.c_str(), line.c_str());
            const std::string expected = substituted(c.message, d);
            if (prefixes.count(expected)) {
                EXPECT_EQ(line.rfind("pathlab: error: " + prefixes.at(expected), 0), 0u) << line;
                EXPECT_NE(line.find(mentions.at(expected)), std::string::npos) << line;
            } else {
                EXPECT_EQ(line, "pathlab: error: " + expected);
            }
            if (!existing && !output.empty()) {
                EXPECT_FALSE(fs::exists(output)) << output;
            }
            EXPECT_EQ(snapshot(dir), before) << args;  // nothing new, nothing changed
            if (existing) fs::remove_all(output);
        }
    }
}

}  // namespace
}  // namespace pathlab
