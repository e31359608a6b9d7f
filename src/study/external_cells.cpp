#include "study/external_cells.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>

#include "core/atomic_file.h"
#include "core/error.h"
#include "metrics/error_map.h"
#include "metrics/error_spectrum.h"
#include "study/content_hash.h"
#include "study/files.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;

// Images measured side by side: enough to keep the cores busy with FLIP's
// single-threaded parts and the PNG encoding, few enough to hold in memory.
constexpr size_t kBatch = 8;

struct PendingCell {
    const ExternalImage* image = nullptr;
    CellKey key;
    std::string hash;
};

std::string stemOf(const CellKey& k) {
    return "images/" + k.scene + "/" + k.sampler + "/spp" + std::to_string(k.spp) + "-seed" +
           std::to_string(k.seed);
}

// The same pictures as the study's own seed-0 cells: the tone-mapped image
// and the two error maps, the image last (what the report looks for).
void writeSeedZeroPictures(const fs::path& dir, const CellKey& key, const Image& image,
                           const ExternalTarget& target, const CellMetrics& m) {
    const std::string stem = (dir / stemOf(key)).string();
    tbb::parallel_invoke(
        [&] {
            if (!m.flipMap.empty())
                writeErrorMap(stem + "-flip.png", m.flipMap, image.width, image.height);
        },
        [&] {
            writeErrorMap(stem + "-relse.png", relativeSquaredErrorMap(target.reference, image),
                          image.width, image.height);
            writeFileAtomic(stem + "-spectrum.csv", errorSpectrumCsv(m.errorSpectrum));
        });
    writeImage(stem + ".png", image, target.exposure);
}

CellRow measureOne(const PendingCell& cell, const ExternalTarget& target, const fs::path& dir) {
    const ExternalImage& source = *cell.image;
    const Image image = readImage(source.path);
    const Image& ref = target.reference;
    if (image.width != ref.width || image.height != ref.height)
        throw InputError("'" + source.path + "' is " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + ", the reference of scene '" +
                         target.scene + "' is " + std::to_string(ref.width) + "x" +
                         std::to_string(ref.height));
    const CellMetrics m = target.meter.measure(image);
    if (cell.key.seed == 0) writeSeedZeroPictures(dir, cell.key, image, target, m);
    CellRow row;
    row.key = cell.key;
    row.seconds = source.seconds;
    row.mse = m.mse;
    row.rmse = m.rmse;
    row.relmse = m.relmse;
    row.flip = m.flip;
    row.flipMedian = m.flipMedian;
    row.psnr = m.psnr;
    row.image = source.path;
    row.width = image.width;
    row.height = image.height;
    row.gitCommit = sourceGitCommit();
    row.finishedAt = isoTimestampUtc();
    row.mseEdge = m.mseEdge;
    row.mseRest = m.mseRest;
    row.bias = m.bias;
    row.lowFrequencyFraction = m.lowFrequencyFraction;
    row.sourceHash = cell.hash;
    return row;
}

}  // namespace

ExternalRun measureExternalCells(const ExternalRenders& renders, const ExternalTarget& target,
                                 const fs::path& studyDir, ResultsStore& store,
                                 StudyProgress& progress) {
    ExternalRun run;
    std::vector<PendingCell> todo;
    for (const ExternalImage& image : renders.images) {
        const CellKey key{target.scene, externalSamplerName(*renders.spec, image.sampler),
                          image.spp, image.seed};
        ContentHash hash;
        hash.file(image.path);
        const auto row = store.cell(key);
        const bool picturesThere =
            key.seed != 0 || fs::is_regular_file(studyDir / (stemOf(key) + ".png"));
        if (row && row->sourceHash == hash.hex() && picturesThere) {
            progress.skipped(target.workPerCell);
            ++run.skipped;
            continue;
        }
        todo.push_back({&image, key, hash.hex()});
    }
    std::error_code ec;
    for (const PendingCell& cell : todo)
        if (cell.key.seed == 0) {
            fs::create_directories((studyDir / stemOf(cell.key)).parent_path(), ec);
            if (ec) throw InputError(writeErrorMessage(studyDir.string(), ec.value()));
        }
    for (size_t begin = 0; begin < todo.size(); begin += kBatch) {
        const size_t end = std::min(todo.size(), begin + kBatch);
        std::vector<CellRow> rows(end - begin);
        tbb::parallel_for(
            begin, end, [&](size_t i) { rows[i - begin] = measureOne(todo[i], target, studyDir); });
        // Committed in the order of the images, whichever finished first.
        for (const CellRow& row : rows) {
            store.putCell(row);
            ++run.measured;
            progress.rendered(row.key.scene + " " + row.key.sampler + " " +
                                  std::to_string(row.key.spp) + " spp seed " +
                                  std::to_string(row.key.seed),
                              target.workPerCell);
        }
    }
    return run;
}

}  // namespace pathlab
