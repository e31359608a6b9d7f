// The importer's state while it reads a pbrt-v4 file: the graphics state that
// AttributeBegin/End saves and restores (PBRT 4th ed., appendix C; pbrt-v4's
// BasicSceneBuilder), the named things, and the scene being built. Shared by
// the grammar (parser.cpp) and the directives' meanings (options_block.cpp,
// world_shapes.cpp, materials.cpp, world_lights.cpp, world_textures.cpp).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scene/pbrt/importer.h"
#include "scene/pbrt/params.h"
#include "scene/pbrt/transform.h"

namespace pathlab::pbrt {

struct AreaLight {
    Vec3f radiance{1.0f};
    bool twoSided = false;
    float power = -1;  // > 0: the radiance is scaled to this power per shape
    SourceLocation where;
};

struct GraphicsState {
    Matrix4 ctm;  // object-to-world of what comes next
    bool reverseOrientation = false;
    int material = -1;  // index into the scene's materials; -1: pbrt-v4's default diffuse
    std::optional<AreaLight> areaLight;
    bool activeStart = true;  // ActiveTransform includes the start time
    // Attribute "shape" | "light" | "material" | "medium" | "texture" defaults.
    std::map<std::string, ParamSet> attributes;
};

class ImportState {
  public:
    ImportState(const ImportOptions& options, std::string mainDir);

    ImportResult result;
    GraphicsState gs;
    bool inWorld = false;
    Matrix4 cameraFromWorld;  // the CTM at Camera
    SourceLocation cameraWhere;
    float shutterTime = 1, isoScale = 1;  // the film's scale is their product
    std::map<std::string, Matrix4> namedCoordinateSystems;
    std::map<std::string, int> namedMaterials;  // name → material index
    // Named materials used before MakeNamedMaterial defines them: where first
    // used, and by which directive.
    struct PendingMaterial {
        SourceLocation where;
        std::string user;
    };
    std::map<std::string, PendingMaterial> pendingMaterials;
    // Textures by name, float and spectrum apart as in pbrt-v4: index into
    // scene.shadingTextures; images by file and encoding: into scene.textures.
    std::map<std::string, int> floatTextures, spectrumTextures;
    std::map<std::string, int> textureImages;
    int shapeAlpha = -1;                 // the alpha texture of the shape being made (-1: opaque)
    std::map<std::string, int> objects;  // name → index into scene.objects
    int currentObject = -1;              // inside ObjectBegin … ObjectEnd
    std::string mainDir;                 // pbrt-v4 resolves files against it

    // Something pbrt-v4 has and we do not: an error, or under --lenient a
    // warning (`instead` says what is done instead).
    void unsupported(const SourceLocation& where, const std::string& what,
                     const std::string& instead);
    void note(const SourceLocation& where, const std::string& what);
    // Every parameter the directive did not read: unsupported.
    void checkUnused(const ParamSet& params, const std::string& directive);
    // A file named in the scene: relative to the main file's directory (as
    // pbrt-v4), else to `includingDir`. InputError at `where` when missing.
    std::string resolveFile(const std::string& name, const std::string& includingDir,
                            const SourceLocation& where) const;
    // The default material (pbrt-v4: diffuse, reflectance 0.5), made on first use.
    int defaultMaterial();
    bool lenient() const { return options_.lenient; }
    // Counts a shape's triangles against ImportOptions::maxTriangles (only
    // checks, without counting, when !keep: a shape about to be made).
    void addTriangles(size_t count, const SourceLocation& where, bool keep = true);

  private:
    ImportOptions options_;
    int defaultMaterial_ = -1;
    size_t triangles_ = 0;
};

// The directives' meanings (parameters already parsed).
void camera(ImportState& st, const std::string& type, const ParamSet& params,
            const SourceLocation& where);
void film(ImportState& st, const std::string& type, const ParamSet& params,
          const SourceLocation& where);
void pixelFilter(ImportState& st, const std::string& type, const ParamSet& params,
                 const SourceLocation& where);
void sampler(ImportState& st, const std::string& type, const ParamSet& params,
             const SourceLocation& where);
void integrator(ImportState& st, const std::string& type, const ParamSet& params,
                const SourceLocation& where);
// After WorldBegin's options are final: the camera's frame and the film's aspect.
void finishOptions(ImportState& st);

void shape(ImportState& st, const std::string& type, const ParamSet& params,
           const SourceLocation& where, const std::string& includingDir);
// Returns the new material's index.
int material(ImportState& st, const std::string& type, const std::string& name,
             const ParamSet& params, const SourceLocation& where);
// NamedMaterial's and mix's reference to a named material: its index, which
// a later MakeNamedMaterial may fill (pbrt-v4 resolves names at the end).
int namedMaterialRef(ImportState& st, const std::string& name, const SourceLocation& where,
                     const std::string& user);
void makeNamedMaterial(ImportState& st, const std::string& name, const std::string& type,
                       const ParamSet& params, const SourceLocation& where);
// The material's "displacement" and "normalmap" (material_maps.cpp).
void materialMaps(ImportState& st, const ParamSet& params, Material& m);
// At the end of the file: every named material used is defined.
void finishMaterials(ImportState& st);
void areaLightSource(ImportState& st, const std::string& type, const ParamSet& params,
                     const SourceLocation& where);
void lightSource(ImportState& st, const std::string& type, const ParamSet& params,
                 const SourceLocation& where);
// The emission of a shape under the current area light: its radiance, or with
// `power`, the radiance that gives that power to each of the shape's
// `primitives` (pbrt-v4 makes one light per triangle or patch: consecutive
// equal runs of the world-space mesh's triangles) — or, when shapeArea > 0,
// to a shape of that area (pbrt-v4's Sphere::Area and Disk::Area, in the
// shape's own space).
Vec3f areaLightEmission(ImportState& st, const AreaLight& light, const Mesh& mesh,
                        size_t primitives, double shapeArea, const SourceLocation& where);
void texture(ImportState& st, const std::string& name, const std::string& colorType,
             const std::string& type, const ParamSet& params, const SourceLocation& where,
             const std::string& includingDir);
// A material parameter given as "texture NAME": the named texture's index in
// scene.shadingTextures (InputError when no texture of that kind has that
// name); nullopt when the parameter is absent or a constant.
std::optional<int> spectrumTextureParam(ImportState& st, const ParamSet& params,
                                        const std::string& name);
std::optional<int> floatTextureParam(ImportState& st, const ParamSet& params,
                                     const std::string& name);

// RGB of a spectrum-valued parameter (rgb, or blackbody/spectrum where the
// colour can be had); nullopt when absent.
std::optional<Vec3f> rgbParam(ImportState& st, const ParamSet& params, const std::string& name);

}  // namespace pathlab::pbrt
