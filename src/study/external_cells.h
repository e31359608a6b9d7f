// Measuring an external renderer's images as study cells: each image decoded
// once, measured like the study's own cells (every metric, the emitter-region
// split when the scene is known), its PNG and error maps written for seed 0,
// and its row committed with the content hash of its file so that --resume
// skips it while the file is unchanged.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/image.h"
#include "study/cell_metrics.h"
#include "study/external.h"
#include "study/progress.h"
#include "study/results_store.h"

namespace pathlab {

// What the images are measured against.
struct ExternalTarget {
    std::string scene;
    const Image& reference;
    float exposure = 0;
    const CellMeter& meter;
    double workPerCell = 0;  // for the progress line
};

struct ExternalRun {
    int measured = 0, skipped = 0;
};

// Throws InputError naming the file for an image that cannot be read or does
// not have the reference's size.
ExternalRun measureExternalCells(const ExternalRenders& renders, const ExternalTarget& target,
                                 const std::filesystem::path& studyDir, ResultsStore& store,
                                 StudyProgress& progress);

}  // namespace pathlab
