// The pbrt-v4 importer's grammar: tokens, parameter lists, transforms, the
// graphics state, Include, objects, and the one-line errors.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/pbrt/importer.h"
#include "scene/pbrt/params.h"
#include "scene/pbrt/tokenizer.h"
#include "scene/pbrt/transform.h"
#include "scene_test_util.h"

namespace pathlab::pbrt {
namespace {

using test::inputErrorOf;
using test::ScratchDir;

// A world holding `body` after a minimal options block.
std::string world(const std::string& body, const std::string& options = "") {
    return options + "\nWorldBegin\n" + body + "\n";
}

ImportResult load(const std::string& text, bool lenient = false) {
    return importPbrtText(text, "test.pbrt", ".", {lenient});
}

std::string errorOf(const std::string& text, bool lenient = false) {
    return inputErrorOf([&] { load(text, lenient); });
}

const std::string kTriangle =
    R"(Shape "trianglemesh" "point3 P" [0 0 0  1 0 0  0 1 0] "integer indices" [0 1 2])";

void expectNear(Vec3f a, Vec3f b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

TEST(PbrtTokenizer, WordsNumbersStringsBracketsAndComments) {
    Tokenizer tok("Shape # a comment\n \"tri\\\"angle\" [ 1 -2.5e1 ]\"x\"", "f.pbrt");
    Token t = tok.next();
    EXPECT_EQ(t.kind, TokenKind::Word);
    EXPECT_EQ(t.text, "Shape");
    t = tok.next();
    EXPECT_EQ(t.kind, TokenKind::String);
    EXPECT_EQ(t.text, "tri\"angle");
    EXPECT_EQ(t.where.line, 2);
    EXPECT_EQ(t.where.column, 2);
    EXPECT_EQ(tok.next().kind, TokenKind::OpenBracket);
    EXPECT_EQ(tok.next().text, "1");
    t = tok.next();
    EXPECT_EQ(t.kind, TokenKind::Number);
    EXPECT_EQ(t.text, "-2.5e1");
    EXPECT_EQ(tok.next().kind, TokenKind::CloseBracket);
    EXPECT_EQ(tok.next().text, "x");
    EXPECT_EQ(tok.next().kind, TokenKind::End);
}

TEST(PbrtTokenizer, UnterminatedStringNamesItsStart) {
    Tokenizer tok("Shape\n  \"trianglemesh", "f.pbrt");
    tok.next();
    EXPECT_EQ(inputErrorOf([&] { tok.next(); }), "f.pbrt:2:3: unterminated string");
}

TEST(PbrtParams, TypesValuesAndWrongTypes) {
    ImportResult r = load(world(kTriangle, R"(Camera "perspective" "float fov" [ 30 ])"));
    EXPECT_FLOAT_EQ(r.scene.camera.fov, 30);
    EXPECT_EQ(errorOf(world(kTriangle, R"(Camera "perspective" "integer fov" 30)")),
              "test.pbrt:1:22: parameter 'fov' must be of type float, not integer");
    EXPECT_EQ(errorOf(world(kTriangle, R"(Camera "perspective" "float fov" "wide")")),
              "test.pbrt:1:34: expected a number, got 'wide'");
    EXPECT_EQ(errorOf(world(kTriangle, R"(Camera "perspective" "flot fov" 3)")),
              "test.pbrt:1:22: unknown parameter type 'flot'");
    EXPECT_EQ(errorOf(world(R"(Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1])")),
              "test.pbrt:3:22: point3 parameter 'P' needs a multiple of 3 numbers, got 8");
}

TEST(PbrtTransform, DirectivesMatchHandComputedMatrices) {
    // Translate then Scale then Rotate: a point is rotated first.
    const Matrix4 m =
        Matrix4::translate(1, 2, 3) * Matrix4::scale(2, 2, 2) * Matrix4::rotate(90, 0, 0, 1);
    expectNear(m.point({1, 0, 0}), {1, 4, 3});  // (1,0,0) → (0,1,0) → (0,2,0) → (1,4,3)
    expectNear(m.vector({0, 1, 0}), {-2, 0, 0});
    const auto inv = m.inverse();
    ASSERT_TRUE(inv.has_value());
    expectNear(inv->point({1, 4, 3}), {1, 0, 0});
    // Transform's 16 numbers are column-major: the translation is the last four.
    const double v[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
    expectNear(Matrix4::fromColumnMajor(v).point({0, 0, 0}), {5, 6, 7});
    // LookAt: camera +z towards the target, +x = up × dir (left-handed).
    const auto look = Matrix4::lookAt({0, 0, -5}, {0, 0, 0}, {0, 1, 0});
    ASSERT_TRUE(look.has_value());
    expectNear(look->point({0, 0, 0}), {0, 0, 5});
    expectNear(look->point({1, 0, -5}), {1, 0, 0});
    EXPECT_FALSE(Matrix4::lookAt({0, 0, 0}, {0, 1, 0}, {0, 1, 0}).has_value());
    EXPECT_TRUE(Matrix4::scale(-1, 1, 1).swapsHandedness());
    EXPECT_FALSE(Matrix4::rotate(30, 1, 1, 0).swapsHandedness());
}

TEST(PbrtTransform, ShapesTakeTheCurrentTransformAndAttributesRestoreIt) {
    const ImportResult r =
        load(world("Translate 10 0 0\nAttributeBegin\nScale 2 2 2\n" + kTriangle +
                   "\nAttributeEnd\n" + kTriangle + "\nIdentity\n" + kTriangle));
    ASSERT_EQ(r.scene.meshes.size(), 3u);
    expectNear(r.scene.meshes[0].positions[1], {12, 0, 0});
    expectNear(r.scene.meshes[1].positions[1], {11, 0, 0});
    expectNear(r.scene.meshes[2].positions[1], {1, 0, 0});
}

TEST(PbrtTransform, ConcatTransformAndNamedCoordinateSystems) {
    const ImportResult r =
        load(world("Translate 1 0 0\nCoordinateSystem \"here\"\nIdentity\n"
                   "ConcatTransform [1 0 0 0  0 1 0 0  0 0 1 0  0 5 0 1]\n" +
                   kTriangle + "\nCoordSysTransform \"here\"\n" + kTriangle));
    expectNear(r.scene.meshes[0].positions[0], {0, 5, 0});
    expectNear(r.scene.meshes[1].positions[0], {1, 0, 0});
    EXPECT_EQ(errorOf(world("CoordSysTransform \"nowhere\"")),
              "test.pbrt:3:1: CoordSysTransform: no coordinate system named 'nowhere'");
}

// Triangle winding is the emitting side. A mirroring transform keeps the
// authored side (pbrt-v4 flips its normal back when the transform swaps
// handedness); ReverseOrientation turns it over.
Vec3f frontOf(const Mesh& m) {
    const Vec3f p0 = m.positions[m.indices[0]], p1 = m.positions[m.indices[1]],
                p2 = m.positions[m.indices[2]];
    return normalize(cross(p1 - p0, p2 - p0));
}

TEST(PbrtTransform, HandednessAndReverseOrientationOfAreaLights) {
    const std::string light = "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n";
    const ImportResult plain =
        load(world("AttributeBegin\n" + light + kTriangle + "\nAttributeEnd"));
    expectNear(frontOf(plain.scene.meshes[0]), {0, 0, 1});
    const ImportResult mirrored =
        load(world("AttributeBegin\nScale 1 1 -1\n" + light + kTriangle + "\nAttributeEnd"));
    expectNear(frontOf(mirrored.scene.meshes[0]), {0, 0, -1});  // +z mirrored to −z
    const ImportResult mirroredX =
        load(world("AttributeBegin\nScale -1 1 1\n" + light + kTriangle + "\nAttributeEnd"));
    expectNear(frontOf(mirroredX.scene.meshes[0]), {0, 0, 1});  // the plane's normal stays
    const ImportResult reversed = load(world("AttributeBegin\nReverseOrientation\n" + light +
                                             kTriangle + "\nAttributeEnd\n" + kTriangle));
    expectNear(frontOf(reversed.scene.meshes[0]), {0, 0, -1});
    EXPECT_EQ(reversed.scene.meshes[0].emission.x, 1);
    EXPECT_EQ(reversed.scene.meshes[1].emission.x, 0);  // AttributeEnd ended the light
}

TEST(PbrtTransform, ALightWithNormalsEmitsTowardsThem) {
    const ImportResult r = load(world(
        "AreaLightSource \"diffuse\"\n"
        R"(Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "normal N" [0 0 -1 0 0 -1 0 0 -1])"));
    expectNear(frontOf(r.scene.meshes[0]), {0, 0, -1});
}

TEST(PbrtState, TransformBeginSavesTheWholeStateAsAttributeBeginDoes) {
    // pbrt-v4 reads TransformBegin/End as AttributeBegin/End.
    const ImportResult r =
        load(world("TransformBegin\nAreaLightSource \"diffuse\"\n"
                   "Translate 0 0 3\nAttributeEnd\n" +
                   kTriangle));
    ASSERT_EQ(r.scene.meshes.size(), 1u);
    EXPECT_EQ(r.scene.meshes[0].emission.x, 0);
    expectNear(r.scene.meshes[0].positions[0], {0, 0, 0});
}

TEST(PbrtState, ActiveTransformIsPartOfTheGraphicsState) {
    const ImportResult r =
        load(world("AttributeBegin\nActiveTransform EndTime\nTranslate 5 0 0\nAttributeEnd\n"
                   "Translate 0 1 0\n" +
                       kTriangle,
                   "ActiveTransform EndTime\n"));
    EXPECT_FALSE(r.notes.empty());                          // no motion blur: said once per use
    expectNear(r.scene.meshes[0].positions[0], {0, 1, 0});  // WorldBegin reset it to All
}

TEST(PbrtState, OptionTakesANameAndAValue) {
    const ImportResult r = load(world(kTriangle,
                                      "Option \"disablepixeljitter\" true\n"
                                      "Option \"seed\" 3\n"));
    EXPECT_EQ(r.notes.size(), 2u);
}

TEST(PbrtState, ImportKeepsTheImportersGraphicsState) {
    ScratchDir dir;
    dir.write("part.pbrt", "Material \"conductor\"\nTranslate 0 0 7\n" + kTriangle +
                               "\n"
                               "MakeNamedMaterial \"m\" \"string type\" \"dielectric\"\n");
    const std::string main = dir.write("main.pbrt", world("Import \"part.pbrt\"\n" + kTriangle +
                                                          "\nNamedMaterial \"m\"\n" + kTriangle));
    const ImportResult r = importPbrtFile(main);
    ASSERT_EQ(r.scene.meshes.size(), 3u);
    const auto type = [&](size_t i) {
        return r.scene.materials[size_t(r.scene.meshes[i].material)].type;
    };
    EXPECT_EQ(type(0), MaterialType::Conductor);  // inside the import: its own state
    expectNear(r.scene.meshes[0].positions[0], {0, 0, 7});
    EXPECT_EQ(type(1), MaterialType::Diffuse);  // after it: the importer's state again
    expectNear(r.scene.meshes[1].positions[0], {0, 0, 0});
    EXPECT_EQ(type(2), MaterialType::Dielectric);  // named things come back
}

TEST(PbrtInclude, RelativeToTheIncludingFileAndDepthLimited) {
    ScratchDir dir;
    std::filesystem::create_directories(dir.path() / "geometry");
    dir.write("geometry/tri.pbrt", kTriangle + "\nInclude \"more.pbrt\"\n");
    dir.write("geometry/more.pbrt", "Translate 0 0 1\n" + kTriangle + "\n");
    const std::string main =
        dir.write("main.pbrt", world("Include \"geometry/tri.pbrt\"\n" + kTriangle));
    const ImportResult r = importPbrtFile(main);
    ASSERT_EQ(r.scene.meshes.size(), 3u);
    expectNear(r.scene.meshes[2].positions[0], {0, 0, 1});  // an Include shares the state
    dir.write("loop.pbrt", "Include \"loop.pbrt\"\n");      // includes itself
    const std::string loop = dir.write("looping.pbrt", world("Include \"loop.pbrt\""));
    EXPECT_NE(inputErrorOf([&] { importPbrtFile(loop); }).find("Include nested more than 64 deep"),
              std::string::npos);
    const std::string missing = dir.write("missing.pbrt", world("Include \"nope.pbrt\""));
    EXPECT_EQ(inputErrorOf([&] { importPbrtFile(missing); }),
              missing + ":3:1: file '" + (dir.path() / "nope.pbrt").string() + "' does not exist");
}

TEST(PbrtObjects, InstancesShareOneDefinition) {
    const ImportResult r = load(world("ObjectBegin \"tri\"\nTranslate 0 0 1\n" + kTriangle +
                                      "\nObjectEnd\nObjectInstance \"tri\"\n"
                                      "Translate 5 0 0\nObjectInstance \"tri\"\n"
                                      "Rotate 90 0 0 1\nObjectInstance \"tri\"\n"));
    ASSERT_EQ(r.scene.objects.size(), 1u);
    ASSERT_EQ(r.scene.objects[0].meshes.size(), 1u);
    EXPECT_TRUE(r.scene.meshes.empty());
    // The object's own transform is applied once, at definition.
    expectNear(r.scene.objects[0].meshes[0].positions[1], {1, 0, 1});
    ASSERT_EQ(r.scene.instances.size(), 3u);
    expectNear(r.scene.instances[1].objectToWorld.point({1, 0, 1}), {6, 0, 1});
    expectNear(r.scene.instances[2].objectToWorld.point({1, 0, 1}), {5, 1, 1});
    EXPECT_EQ(errorOf(world("ObjectInstance \"none\"")),
              "test.pbrt:3:1: ObjectInstance: no object named 'none'");
    EXPECT_EQ(errorOf(world("ObjectEnd")),
              "test.pbrt:3:1: unbalanced ObjectEnd: no ObjectBegin is open");
}

TEST(PbrtErrors, OneLineNamingFileLineAndColumn) {
    EXPECT_EQ(errorOf(world("Shpe \"sphere\"")), "test.pbrt:3:1: unknown directive 'Shpe'");
    EXPECT_EQ(errorOf(world("AttributeEnd")),
              "test.pbrt:3:1: unbalanced AttributeEnd: no AttributeBegin is open");
    EXPECT_EQ(errorOf(world("AttributeBegin\n" + kTriangle)),
              "test.pbrt:3:1: this block is never closed (no AttributeEnd/TransformEnd)");
    EXPECT_EQ(errorOf(world("NamedMaterial \"gold\"")),
              "test.pbrt:3:1: NamedMaterial: no material named 'gold'");
    EXPECT_EQ(
        errorOf(world(
            R"(Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 3])")),
        "test.pbrt:3:1: trianglemesh: index 3 (entry 2) is out of range (3 vertices)");
    EXPECT_EQ(
        errorOf(world(
            R"(Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2)")),
        "test.pbrt:3:71: unterminated '[' in the values of 'integer indices'");
    EXPECT_EQ(errorOf(world("", "WorldBegin")),
              "test.pbrt:2:1: WorldBegin is not allowed after WorldBegin");
    EXPECT_EQ(errorOf("Shape \"sphere\""), "test.pbrt:1:1: Shape is only allowed after WorldBegin");
    EXPECT_EQ(errorOf(world("", "Integrator \"bdpt\"")),
              "test.pbrt:1:1: integrator 'bdpt' is not supported (pathlab renders with a path "
              "tracer: use \"path\" or \"volpath\")");
    EXPECT_EQ(errorOf(R"(Film "rgb")"), "test.pbrt: no WorldBegin: the file describes no scene");
}

TEST(PbrtLenient, UnsupportedIsAnErrorOrASubstitutionWithAWarning) {
    const std::string hair =
        world("Material \"hair\" \"rgb reflectance\" [0.2 0.3 0.4]\n" + kTriangle);
    EXPECT_EQ(errorOf(hair),
              "test.pbrt:3:1: material 'hair' (or these parameters of it) is not "
              "supported (--lenient substitutes diffuse grey)");
    const ImportResult r = load(hair, true);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_EQ(r.warnings[0],
              "test.pbrt:3:1: warning: material 'hair' (or these parameters of it) is "
              "not supported; diffuse grey instead");
    const Material& m = r.scene.materials[size_t(r.scene.meshes[0].material)];
    EXPECT_EQ(m.type, MaterialType::Diffuse);
    EXPECT_FLOAT_EQ(m.albedo.x, 0.5f);
    // An unknown parameter is unsupported too.
    EXPECT_EQ(errorOf(world(kTriangle, "Camera \"perspective\" \"float zoom\" 2")),
              "test.pbrt:1:22: parameter \"float zoom\" of Camera \"perspective\" is not "
              "supported (--lenient substitutes nothing (it is ignored))");
}

TEST(PbrtOptions, SamplerIntegratorFilterAndFilmDefaults) {
    const ImportResult none = load(world(kTriangle));
    EXPECT_EQ(none.scene.defaults.sampler, "zsobol");  // pbrt-v4's defaults
    EXPECT_EQ(none.scene.defaults.samplesPerPixel, 16);
    EXPECT_EQ(none.scene.defaults.maxDepth, 5);
    EXPECT_EQ(none.scene.film.filter.type, FilterType::Gaussian);
    EXPECT_EQ(none.scene.resolution.x, 1280);
    const ImportResult r = load(world(kTriangle,
                                      "Sampler \"halton\" \"integer pixelsamples\" 64 \"integer "
                                      "seed\" 7\nIntegrator \"volpath\" \"integer maxdepth\" 3\n"
                                      "PixelFilter \"mitchell\" \"float xradius\" 1.5\n"
                                      "Film \"rgb\" \"integer xresolution\" 64 \"integer "
                                      "yresolution\" 32 \"float iso\" 200\n"));
    EXPECT_EQ(r.scene.defaults.sampler, "halton-rd");  // permutedigits by default
    EXPECT_EQ(r.scene.defaults.samplesPerPixel, 64);
    EXPECT_TRUE(r.scene.defaults.hasSeed);
    EXPECT_EQ(r.scene.defaults.seed, 7u);
    EXPECT_EQ(r.scene.defaults.maxDepth, 3);
    EXPECT_EQ(r.scene.film.filter.type, FilterType::Mitchell);
    EXPECT_FLOAT_EQ(r.scene.film.filter.radius.x, 1.5f);
    EXPECT_FLOAT_EQ(r.scene.film.filter.radius.y, 2);
    EXPECT_EQ(r.scene.resolution.x, 64);
    EXPECT_EQ(r.scene.resolution.y, 32);
    EXPECT_FLOAT_EQ(r.scene.film.scale, 2);
    const auto mapped = [&](const std::string& s) {
        return load(world(kTriangle, "Sampler " + s)).scene.defaults.sampler;
    };
    EXPECT_EQ(mapped("\"sobol\" \"string randomization\" \"none\""), "sobol");
    // pbrt-v4's sobol scrambles with fastowen unless told.
    EXPECT_EQ(mapped("\"sobol\""), "sobol-global-owen");
    EXPECT_EQ(mapped("\"sobol\" \"string randomization\" \"owen\""), "sobol-global-owen");
    EXPECT_EQ(mapped("\"sobol\" \"string randomization\" \"permutedigits\""), "sobol-xor");
    EXPECT_EQ(mapped("\"halton\" \"string randomization\" \"owen\""), "halton-owen");
    EXPECT_EQ(mapped("\"paddedsobol\""), "sobol-owen");
    EXPECT_EQ(mapped("\"pmj02bn\""), "pmj02");
    EXPECT_EQ(mapped("\"independent\""), "independent");
    // pbrt-v4's independent sampler takes 4 samples unless told.
    EXPECT_EQ(load(world(kTriangle, "Sampler \"independent\"")).scene.defaults.samplesPerPixel, 4);
    // No silent swaps: a randomization pathlab lacks is unsupported.
    EXPECT_EQ(errorOf(world(kTriangle, "Sampler \"zsobol\" \"string randomization\" \"none\"")),
              "test.pbrt:1:1: zsobol with randomization 'none' is not supported (--lenient "
              "substitutes zsobol)");
    // A later Film replaces an earlier one: its ISO scales the image once.
    const ImportResult twice = load(world(kTriangle,
                                          "Film \"rgb\" \"float iso\" 200\n"
                                          "Film \"rgb\" \"float iso\" 200\n"));
    EXPECT_FLOAT_EQ(twice.scene.film.scale, 2);
}

TEST(PbrtCamera, ALookAtPinholeBecomesTheClassicCamera) {
    const ImportResult r = load(world(kTriangle,
                                      "Scale -1 1 1\nLookAt 278 273 -800 278 273 0 0 1 0\n"
                                      "Camera \"perspective\" \"float fov\" 37.5\n"
                                      "Film \"rgb\" \"integer xresolution\" 100 "
                                      "\"integer yresolution\" 200\n"));
    const Camera& c = r.scene.camera;
    EXPECT_FALSE(c.pbrtFrame);
    expectNear(c.eye, {278, 273, -800}, 1e-3f);
    expectNear(normalize(c.target - c.eye), {0, 0, 1});
    expectNear(c.up, {0, 1, 0});
    // Portrait: pbrt-v4's 37.5° spans the width; the vertical angle is wider.
    const float tanX = std::tan(37.5f * kPi / 360), tanY = std::tan(c.fovY * kPi / 360);
    EXPECT_NEAR(tanY * 0.5f, tanX, 1e-5f);
}

TEST(PbrtCamera, OtherCamerasKeepPbrtsFrame) {
    // Without Scale −1 1 1, pbrt-v4's image right is up × dir = world +x here.
    const ImportResult r = load(world(kTriangle,
                                      "LookAt 0 0 -5 0 0 0 0 1 0\n"
                                      "Camera \"perspective\" \"float lensradius\" 0.1 "
                                      "\"float focaldistance\" 5\n"));
    const Camera& c = r.scene.camera;
    EXPECT_TRUE(c.pbrtFrame);
    expectNear(c.eye, {0, 0, -5});
    expectNear(c.axisX, {1, 0, 0});
    expectNear(c.axisY, {0, 1, 0});
    expectNear(c.axisZ, {0, 0, 1});
    EXPECT_FLOAT_EQ(c.lensRadius, 0.1f);
    EXPECT_FLOAT_EQ(c.focalDistance, 5);
}

}  // namespace
}  // namespace pathlab::pbrt
