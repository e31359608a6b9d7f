// The steps of `pathlab study` (runner.cpp), shared by the single-process run
// and the run across MPI ranks (mpi_study.cpp), so that both make the same
// cells from the same code.
#pragma once

#include <filesystem>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/render_scene.h"
#include "study/cell_metrics.h"
#include "study/external.h"
#include "study/progress.h"
#include "study/reference_cache.h"
#include "study/reference_ranges.h"
#include "study/results_store.h"
#include "study/runner.h"
#include "study/spec.h"

namespace pathlab::study_steps {

// Flip, tone mapping and file writing per cell, in samples per pixel: makes
// the ETA right for the many cheap low-spp cells.
inline constexpr double kCellOverheadSpp = 4.0;

struct SceneJob {
    StudyScene scene;
    std::unique_ptr<RenderScene> render;
    std::string cacheKey;
    std::string contentHash;  // sceneContentHash
    // The emitter-edge pixels at the study's resolution (emitterEdgePixels):
    // every MSE is also reported over them and over the rest.
    std::vector<uint8_t> edgeMask;
    int64_t edgePixels = 0;
};

// An [[external]] table's images, found before the directory is touched,
// and the reference it names (empty when it uses the study's).
struct ExternalJob {
    ExternalRenders renders;
    Image reference;
};

// Everything a cell needs besides its key.
struct StudyContext {
    const StudySpec& spec;
    const StudyOptions& options;
    ResultsStore& store;
    StudyProgress& progress;
    StudyRun& run;
    int threads = 0;  // as used, for the record
    const std::vector<ExternalJob>& externals;
};

// What rendering and measuring a cell needs, without the results store: all
// a rank that only renders has.
struct CellWriter {
    const StudySpec& spec;
    std::filesystem::path dir;
    int threads = 0;  // 0: all cores
};

// One render of the study: a cell, or all of a progressive sampler's missing
// cells at one seed, the smaller spp taken as prefixes of the largest — the
// same images as rendering each alone (RenderSettings::prefixSpp), for the
// cost of the largest. A sampler the seed does not randomise (SamplerInfo::
// randomized, tested) gives every seed the same image, so one render serves
// all its missing seeds: their cells are the same image and measurements.
struct CellRender {
    std::string sampler;
    int seed = 0;                // the seed rendered: the smallest of `cells`
    std::vector<int> spp;        // ascending: the render's spp and its prefixes
    std::vector<CellKey> cells;  // what it completes, each spp of `spp` at least once
};

// One cell's measurements and images, ready to be committed as its row.
struct MeasuredCell {
    CellKey key;
    double seconds = 0;
    uint64_t nonFinite = 0;
    CellMetrics metrics;
};

// The outermost directory of `dir` that does not exist yet, or "" when `dir`
// exists: what removing the study's files must remove.
std::filesystem::path firstMissingDirectory(const std::filesystem::path& dir);

// The files a study begins with. Should writing them fail (a full disk, a
// directory that cannot be written), what was created is removed again, so
// the directory is left as it was (also when a rank of a study across MPI
// ranks cannot reach it).
class DirectorySetup {
  public:
    explicit DirectorySetup(const std::filesystem::path& dir)
        : dir_(dir), missing_(firstMissingDirectory(dir)) {
        std::error_code ec;
        for (const char* name : kEntries)
            existed_.push_back(std::filesystem::exists(dir / name, ec));
    }
    void undo() const {
        std::error_code ec;
        if (!missing_.empty()) {
            std::filesystem::remove_all(missing_, ec);
            return;
        }
        for (size_t i = 0; i < std::size(kEntries); ++i)
            if (!existed_[i]) std::filesystem::remove_all(dir_ / kEntries[i], ec);
    }

  private:
    static constexpr const char* kEntries[] = {"references",         "spec.toml",
                                               "results.sqlite",     "results.sqlite-wal",
                                               "results.sqlite-shm", "results.sqlite-journal"};
    std::filesystem::path dir_, missing_;
    std::vector<bool> existed_;
};

double pixels(const StudySpec& spec);
double cellWork(const StudySpec& spec, const CellKey& key);
std::string cellLabel(const CellKey& key);
void createDirectories(const std::filesystem::path& dir);

std::vector<SceneJob> loadScenes(const StudySpec& spec);
std::vector<ExternalJob> findExternals(const StudySpec& spec);
int externalCellCount(const std::vector<ExternalJob>& externals);
void checkDirectory(const StudySpec& spec, const std::vector<SceneJob>& jobs,
                    const StudyOptions& options);
std::unique_ptr<ResultsStore> beginStudyFiles(const StudySpec& spec,
                                              const std::vector<SceneJob>& jobs,
                                              const StudyOptions& options);
double totalWork(const StudySpec& spec, const std::vector<SceneJob>& jobs);

// The scene's cells not yet in the results; the others are counted as skipped.
std::vector<CellKey> unfinishedCells(const SceneJob& job, StudyContext& ctx);
// A scene's reference: findReference takes it from the cache or the study
// directory; else it is rendered in sample ranges (reference_ranges.h), each
// saved as it is done (saveReferenceRange), those already saved skipped
// (missingReferenceRanges), then merged and cached by finishReference, which
// renders any range still missing. obtainReference does all of it in this
// process.
std::optional<Reference> findReference(const SceneJob& job, StudyContext& ctx);
std::vector<int> missingReferenceRanges(const SceneJob& job, StudyContext& ctx);
void saveReferenceRange(const SceneJob& job, const RangeSums& range, StudyContext& ctx);
Reference finishReference(const SceneJob& job, StudyContext& ctx);
Reference obtainReference(const SceneJob& job, StudyContext& ctx);
// "wolf reference samples 256…511 (range 2 of 16)"
std::string rangeLabel(const SceneJob& job, const StudySpec& spec, int index);
void recordReference(const SceneJob& job, const Reference& ref, StudyContext& ctx);
std::vector<CellRender> planRenders(const std::vector<CellKey>& todo);

// Renders one CellRender, measures its cells and writes their images
// (atomically); returns their measurements in the order of `cells.cells`.
std::vector<MeasuredCell> renderCellGroup(const SceneJob& job, const Reference& ref,
                                          const CellMeter& meter, const CellRender& cells,
                                          const CellWriter& writer);
void commitCell(const MeasuredCell& cell, StudyContext& ctx);

void measureExternalsOfScene(const SceneJob& job, const Reference& ref, const CellMeter& meter,
                             StudyContext& ctx);
void measureExternalWithReference(const ExternalJob& e, const std::vector<SceneJob>& jobs,
                                  StudyContext& ctx);
void finishStudy(const StudySpec& spec, const StudyOptions& o, ResultsStore& store, StudyRun& run);

}  // namespace pathlab::study_steps
