// A material's bump and normal maps (pbrt-v4 File Format, "Materials":
// "displacement", a float texture or constant, and "normalmap", an image
// file; pbrt-v4's BasicScene::startLoadingNormalMaps reads the latter with
// the linear encoding and needs its R, G and B). Applied at each hit by the
// renderer (render/bump_mapping.h).
#include <cmath>

#include "core/error.h"
#include "scene/pbrt/parser_state.h"
#include "scene/texture_loader.h"
#include "scene/textures/image_encoding.h"

namespace pathlab::pbrt {
namespace {

// The normal map's image, read once per file and shared with an imagemap
// of the same file read linearly (world_texture_classes.cpp's key).
int normalMapImage(ImportState& st, const Param& file) {
    if (file.type != ParamType::String || file.strings.size() != 1)
        throw errorAt(file.where, "\"normalmap\" needs one \"string\" file name");
    const std::string path = st.resolveFile(file.strings[0], st.mainDir, file.where);
    const std::string key = path + "\nlinear";
    if (const auto it = st.textureImages.find(key); it != st.textureImages.end()) return it->second;
    Texture image;
    try {
        image = loadTexture(path);
    } catch (const InputError& e) {
        throw errorAt(file.where, e.what());
    }
    // loadTexture decodes PNG as sRGB; a normal map's code values are linear.
    reencodeTexels(image, ImageEncoding{ImageEncoding::Linear});
    st.result.scene.textures.push_back(std::move(image));
    const int index = int(st.result.scene.textures.size()) - 1;
    st.textureImages[key] = index;
    return index;
}

}  // namespace

void materialMaps(ImportState& st, const ParamSet& ps, Material& m) {
    if (const Param* file = ps.find("normalmap")) {
        file->used = true;
        m.normalMap = normalMapImage(st, *file);
    }
    if (const auto texture = floatTextureParam(st, ps, "displacement")) {
        m.displacementTexture = *texture;
    } else if (const Param* value = ps.find("displacement")) {
        // A constant height, as pbrt-v4's GetFloatTextureOrNull makes one.
        ShadingTexture node;
        node.kind = TextureKind::Constant;
        node.isFloat = true;
        node.value = Vec3f(ps.getFloat("displacement", 0));
        if (!std::isfinite(node.value.x))
            throw errorAt(value->where, "\"displacement\" must be a finite number");
        st.result.scene.shadingTextures.push_back(node);
        m.displacementTexture = int(st.result.scene.shadingTextures.size()) - 1;
    }
}

}  // namespace pathlab::pbrt
