// Another renderer's images in a study ([[external]] in docs/study-spec.toml):
// the files its pattern matches, as cells "name:sampler" × spp × seed, with
// their render times. Found and checked before a study touches its directory;
// the images themselves are decoded once, when they are measured.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"
#include "core/math.h"
#include "study/spec.h"

namespace pathlab {

struct ExternalImage {
    std::string sampler;  // as the file names it, without the renderer's prefix
    int spp = 0, seed = 0;
    std::string path;    // absolute
    double seconds = 0;  // from the times file; 0 without one
};

struct ExternalRenders {
    const ExternalSpec* spec = nullptr;
    // Seeds outermost, then spp, then samplers, like the study's own cells.
    std::vector<ExternalImage> images;
};

// The sampler name a study gives an external renderer's sampler.
std::string externalSamplerName(const ExternalSpec& spec, const std::string& sampler);

// Every image an [[external]] table names. Throws InputError (one line naming
// the key or the file) for a pattern without each of {sampler}, {spp} and
// {seed} exactly once, a pattern that matches no file, two files for one
// cell, a file missing from the grid of the samplers, spp and seeds found,
// and a times file that cannot be read or lacks a row for an image.
ExternalRenders findExternalImages(const ExternalSpec& spec);

// Reads only each image's header (EXR, PNG; a PFM is read whole) and throws
// InputError naming the file for one that cannot be read or is not `size`:
// a bad image stops the study before it writes anything.
void checkExternalImageSizes(const ExternalRenders& renders, Vec2i size);

// The file name a pattern gives one cell.
std::string externalImagePath(const std::string& pattern, const std::string& sampler, int spp,
                              int seed);

}  // namespace pathlab
