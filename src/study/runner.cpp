#include "study/runner.h"

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <map>
#include <memory>
#include <tuple>

#include "core/atomic_file.h"
#include "core/error.h"
#include "metrics/error_map.h"
#include "metrics/error_spectrum.h"
#include "render/emitter_edges.h"
#include "render/renderer.h"
#include "sampling/registry.h"
#include "scene/loader.h"
#include "study/analysis.h"
#include "study/cell_metrics.h"
#include "study/exports.h"
#include "study/external.h"
#include "study/external_cells.h"
#include "study/files.h"
#include "study/progress.h"
#include "study/reference_cache.h"
#include "study/results_store.h"
#include "study/runner_steps.h"
#include "study/summary.h"

namespace pathlab {
namespace study_steps {
namespace fs = std::filesystem;

std::string cellStem(const CellKey& k) {
    return "images/" + k.scene + "/" + k.sampler + "/spp" + std::to_string(k.spp) + "-seed" +
           std::to_string(k.seed);
}

double pixels(const StudySpec& spec) {
    return double(spec.resolution.x) * spec.resolution.y;
}

// The samples a cell adds to the study. A progressive sampler's cells are
// prefixes of one render (see planRenders), so each adds only the samples
// beyond the next smaller spp of the list; a sampler the seed does not
// randomise is rendered for its first seed only, the others are copies.
double cellWork(const StudySpec& spec, const CellKey& key) {
    const SamplerInfo& info = samplerInfo(key.sampler);
    if (!info.randomized && key.seed > 0) return pixels(spec) * kCellOverheadSpp;
    int previous = 0;
    if (info.progressive)
        for (int spp : spec.spp)
            if (spp < key.spp) previous = std::max(previous, spp);
    return pixels(spec) * (key.spp - previous + kCellOverheadSpp);
}

std::vector<CellKey> sceneCells(const StudySpec& spec, const std::string& scene) {
    // Seeds outermost: a study cut short still has every sampler at every
    // spp for the first seeds, which is a complete comparison.
    std::vector<CellKey> out;
    for (int seed = 0; seed < spec.seeds; ++seed)
        for (int spp : spec.spp)
            for (const std::string& sampler : spec.samplers)
                out.push_back({scene, sampler, spp, seed});
    return out;
}

bool cellComplete(const fs::path& dir, const ResultsStore& store, const CellKey& key) {
    const auto row = store.cell(key);
    if (!row || !fs::is_regular_file(dir / row->image)) return false;
    return key.seed != 0 || fs::is_regular_file(dir / (cellStem(key) + ".png"));
}

// Empty, or holding only directories and temporaries: what a run killed
// before it wrote spec.toml leaves, which is no study yet.
bool directoryIsEmpty(const fs::path& dir) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) return true;
    for (auto it = fs::recursive_directory_iterator(dir, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
        if (!it->is_directory(ec) && !isTemporaryName(it->path().filename().string())) return false;
    return !ec;
}

void createDirectories(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw InputError(writeErrorMessage(dir.string(), ec.value()));
}

// The key under which the study table keeps a scene's content hash.
std::string sceneHashKey(const std::string& scene) {
    return "scene_hash." + scene;
}

// A resumed study must go on with the scenes it began with: a scene file
// edited since would mix cells of two scenes in one comparison. Studies
// recorded before the hashes were kept have none, and are taken as they are.
void requireSameScenes(const fs::path& dir, const std::vector<SceneJob>& jobs) {
    const fs::path database = dir / "results.sqlite";
    std::error_code ec;
    if (!fs::is_regular_file(database, ec)) return;
    const auto values = ResultsStore::readStudyValues(database.string());
    for (const SceneJob& job : jobs) {
        const auto stored = values.find(sceneHashKey(job.scene.name));
        if (stored != values.end() && stored->second != job.contentHash)
            throw InputError("'" + dir.string() + "' holds a study whose scene '" + job.scene.name +
                             "' (" + job.scene.source +
                             ") has changed since it began: choose another directory");
    }
}

// Every check of the study directory, before anything is written to it.
void checkDirectory(const StudySpec& spec, const std::vector<SceneJob>& jobs,
                    const StudyOptions& o) {
    const fs::path& dir = o.dir;
    const bool empty = directoryIsEmpty(dir);
    if (!empty && !o.resume)
        throw InputError("'" + dir.string() +
                         "' is not empty: add --resume to continue the study in it, or choose "
                         "another directory");
    if (empty) return;
    if (!fs::is_regular_file(dir / "spec.toml"))
        throw InputError("'" + dir.string() + "' is not a study directory (no spec.toml)");
    const std::string diff = firstSpecDifference(loadStudySpec((dir / "spec.toml").string()), spec);
    if (!diff.empty())
        throw InputError("'" + dir.string() + "' holds a study whose '" + diff +
                         "' differs from this spec: choose another directory");
    requireSameScenes(dir, jobs);
}

fs::path firstMissingDirectory(const fs::path& dir) {
    std::error_code ec;
    fs::path missing;
    for (fs::path p = fs::absolute(dir).lexically_normal(); !p.empty() && !fs::exists(p, ec);
         p = p.parent_path()) {
        missing = p;
        if (p == p.parent_path()) break;
    }
    return missing;
}

std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : ",") + s;
    return out;
}

void recordStudy(const StudySpec& spec, const std::vector<SceneJob>& jobs, ResultsStore& store) {
    const auto existing = store.studyValues();
    const auto created = existing.find("created_at");
    std::map<std::string, std::string> values{
        {"name", spec.name},
        {"created_at", created != existing.end() ? created->second : isoTimestampUtc()},
        {"git_commit", sourceGitCommit()},
        {"width", std::to_string(spec.resolution.x)},
        {"height", std::to_string(spec.resolution.y)},
        {"max_depth", std::to_string(spec.maxDepth)},
        {"russian_roulette", spec.russianRoulette ? "true" : "false"},
        {"roulette_depth", std::to_string(spec.rouletteDepth)},
        {"spectral", spec.spectral ? "true" : "false"},
        {"wavelengths", spectral::wavelengthSamplingName(spec.wavelengths)},
        {"reference_spp", std::to_string(spec.reference.spp)},
        {"reference_sampler", spec.reference.sampler},
        {"reference_seed", std::to_string(spec.reference.seed)},
        {"time_budget_seconds",
         spec.timeBudgetSeconds ? nlohmann::json(*spec.timeBudgetSeconds).dump() : ""},
        {"metrics", joined(spec.metrics)},
    };
    for (const SceneJob& job : jobs) values[sceneHashKey(job.scene.name)] = job.contentHash;
    store.setStudyValues(values);
}

// Loads every scene before the study directory is touched. A scene that
// cannot be loaded is reported against the spec line that names it.
std::vector<SceneJob> loadScenes(const StudySpec& spec) {
    std::vector<SceneJob> jobs;
    for (const StudyScene& s : spec.scenes) {
        SceneDescription description;
        try {
            description = loadScene(s.source);
        } catch (const InputError& e) {
            if (s.origin.empty()) throw;
            throw InputError(s.origin + " names a scene that cannot be loaded: " + e.what());
        }
        if (!spec.lightSampler.empty()) description.defaults.lightSampler = spec.lightSampler;
        const std::string key = referenceCacheKey(description, s, spec);
        const std::string hash = sceneContentHash(description, s);
        SceneJob job{s, std::make_unique<RenderScene>(std::move(description)), key, hash, {}, 0};
        job.edgeMask = emitterEdgePixels(*job.render, spec.resolution);
        job.edgePixels = std::count(job.edgeMask.begin(), job.edgeMask.end(), uint8_t(1));
        jobs.push_back(std::move(job));
    }
    return jobs;
}

// Creates the directory and its first files, and opens the results.
std::unique_ptr<ResultsStore> beginStudyFiles(const StudySpec& spec,
                                              const std::vector<SceneJob>& jobs,
                                              const StudyOptions& o) {
    const DirectorySetup setup(o.dir);
    try {
        createDirectories(o.dir / "references");
        // What a killed run was writing: never complete, so never used.
        removeStaleTemporaries(o.dir);
        writeTextFileAtomic(o.dir / "spec.toml", studySpecToToml(spec));
        auto store = std::make_unique<ResultsStore>((o.dir / "results.sqlite").string());
        recordStudy(spec, jobs, *store);
        return store;
    } catch (...) {
        setup.undo();
        throw;
    }
}

// The images first, each renamed into place; the row last, in one
// transaction: a row always points at complete images.
void writeCellImages(const fs::path& dir, const CellKey& key, const Image& image,
                     const Reference& ref, const CellMetrics& m) {
    const std::string stem = (dir / cellStem(key)).string();
    if (key.seed != 0) return writeImage(stem + ".exr", image);
    // Encoding is single-threaded: the three files side by side.
    tbb::parallel_invoke(
        [&] { writeImage(stem + ".exr", image); },
        [&] {
            if (!m.flipMap.empty())
                writeErrorMap(stem + "-flip.png", m.flipMap, image.width, image.height);
        },
        [&] {
            writeErrorMap(stem + "-relse.png", relativeSquaredErrorMap(ref.image, image),
                          image.width, image.height);
            writeFileAtomic(stem + "-spectrum.csv", errorSpectrumCsv(m.errorSpectrum));
        });
    writeImage(stem + ".png", image, ref.exposure);  // last: cellComplete looks for it
}

std::string cellLabel(const CellKey& k) {
    return k.scene + " " + k.sampler + " " + std::to_string(k.spp) + " spp seed " +
           std::to_string(k.seed);
}

std::vector<CellRender> planRenders(const std::vector<CellKey>& todo) {
    std::vector<CellRender> plan;
    // (sampler, seed or −1 for every seed, spp or −1 for every spp) → plan index
    std::map<std::tuple<std::string, int, int>, size_t> grouped;
    for (const CellKey& key : todo) {
        const SamplerInfo& info = samplerInfo(key.sampler);
        const auto group = std::make_tuple(key.sampler, info.randomized ? key.seed : -1,
                                           info.progressive ? -1 : key.spp);
        const auto [it, added] = grouped.try_emplace(group, plan.size());
        if (added) plan.push_back({key.sampler, key.seed, {}, {}});
        CellRender& r = plan[it->second];
        r.seed = std::min(r.seed, key.seed);
        if (std::find(r.spp.begin(), r.spp.end(), key.spp) == r.spp.end()) r.spp.push_back(key.spp);
        r.cells.push_back(key);
    }
    for (CellRender& r : plan) std::sort(r.spp.begin(), r.spp.end());
    return plan;
}

MeasuredCell measureAndWriteCell(const Reference& ref, const CellMeter& meter, const CellKey& key,
                                 const Image& image, double seconds, uint64_t nonFinite,
                                 const CellWriter& ctx) {
    MeasuredCell cell{key, seconds, nonFinite, meter.measure(image)};
    writeCellImages(ctx.dir, key, image, ref, cell.metrics);
    return cell;
}

// A cell whose image is another cell's (the same render, another seed of a
// sampler the seed does not randomise): the same measurements, its own files.
MeasuredCell copyMeasuredCell(const MeasuredCell& measured, const Reference& ref,
                              const CellKey& key, const Image& image, const CellWriter& ctx) {
    MeasuredCell cell = measured;
    cell.key = key;
    writeCellImages(ctx.dir, key, image, ref, cell.metrics);
    return cell;
}

void commitCell(const MeasuredCell& cell, StudyContext& ctx) {
    const CellMetrics& m = cell.metrics;
    CellRow row{cell.key,
                cell.seconds,
                m.mse,
                m.rmse,
                m.relmse,
                m.flip,
                m.flipMedian,
                m.psnr,
                int64_t(cell.nonFinite),
                cellStem(cell.key) + ".exr",
                ctx.spec.resolution.x,
                ctx.spec.resolution.y,
                ctx.spec.maxDepth,
                ctx.threads,
                sourceGitCommit(),
                isoTimestampUtc(),
                m.mseEdge,
                m.mseRest,
                m.bias,
                m.lowFrequencyFraction,
                {}};
    ctx.store.putCell(row);
    ++ctx.run.cellsRendered;
    ctx.progress.rendered(cellLabel(cell.key), cellWork(ctx.spec, cell.key));
}

std::vector<MeasuredCell> renderCellGroup(const SceneJob& job, const Reference& ref,
                                          const CellMeter& meter, const CellRender& cells,
                                          const CellWriter& ctx) {
    RenderSettings s = studyRenderSettings(ctx.spec, ctx.threads);
    s.sampler = cells.sampler;
    s.samplesPerPixel = cells.spp.back();
    s.prefixSpp.assign(cells.spp.begin(), cells.spp.end() - 1);
    s.seed = uint64_t(cells.seed);
    const RenderOutput out = render(*job.render, s);
    std::vector<PrefixImage> images = out.prefixes;
    images.push_back(
        {s.samplesPerPixel, out.image, out.varianceOfMean, out.stats.seconds, out.stats.nonFinite});
    // The cells' FLIP, error maps and file encoding are measured side by side
    // (much of it is single-threaded); their rows are then committed in spp
    // order, one transaction each, so the store's order does not depend on
    // which finished first.
    createDirectories((ctx.dir / cellStem({job.scene.name, cells.sampler, 1, 0})).parent_path());
    // Each spp is measured once, by its first cell; the cells of other seeds
    // with the same image take those measurements.
    std::vector<const CellKey*> first(images.size(), nullptr);
    std::vector<size_t> imageOf(cells.cells.size());
    for (size_t c = 0; c < cells.cells.size(); ++c) {
        const auto at = std::find(cells.spp.begin(), cells.spp.end(), cells.cells[c].spp);
        imageOf[c] = size_t(at - cells.spp.begin());
        if (!first[imageOf[c]]) first[imageOf[c]] = &cells.cells[c];
    }
    std::vector<MeasuredCell> measured(cells.cells.size());
    tbb::parallel_for(size_t(0), images.size(), [&](size_t k) {
        const PrefixImage& p = images[k];
        if (!first[k]) return;
        const MeasuredCell m =
            measureAndWriteCell(ref, meter, *first[k], p.image, p.seconds, p.nonFinite, ctx);
        for (size_t c = 0; c < cells.cells.size(); ++c)
            if (imageOf[c] == k)
                measured[c] = &cells.cells[c] == first[k]
                                  ? m
                                  : copyMeasuredCell(m, ref, cells.cells[c], p.image, ctx);
    });
    return measured;
}

void renderCells(const SceneJob& job, const Reference& ref, const CellMeter& meter,
                 const CellRender& cells, StudyContext& ctx) {
    const CellWriter writer{ctx.spec, ctx.options.dir, ctx.options.threads};
    // Rows in the order of the plan: seeds, then spp, as the cells were listed.
    for (const MeasuredCell& cell : renderCellGroup(job, ref, meter, cells, writer))
        commitCell(cell, ctx);
}

void measureExternal(const ExternalJob& external, const ExternalTarget& target, StudyContext& ctx) {
    const ExternalRun r =
        measureExternalCells(external.renders, target, ctx.options.dir, ctx.store, ctx.progress);
    ctx.run.cellsRendered += r.measured;
    ctx.run.cellsSkipped += r.skipped;
}

// The external renders of a study scene that use its reference.
void measureExternalsOfScene(const SceneJob& job, const Reference& ref, const CellMeter& meter,
                             StudyContext& ctx) {
    for (const ExternalJob& e : ctx.externals)
        if (e.renders.spec->scene == job.scene.name && e.renders.spec->reference.empty())
            measureExternal(e,
                            {job.scene.name, ref.image, ref.exposure, meter,
                             pixels(ctx.spec) * kCellOverheadSpp},
                            ctx);
}

// An external render with its own reference: measured against that, with the
// emitter-edge split when the scene is the study's and the sizes agree. A
// scene the study does not render gets the reference's row and pictures.
void measureExternalWithReference(const ExternalJob& e, const std::vector<SceneJob>& jobs,
                                  StudyContext& ctx) {
    const std::string& scene = e.renders.spec->scene;
    const float exposure = viewingExposure(e.reference);
    const std::vector<uint8_t>* mask = nullptr;
    const auto job = std::find_if(jobs.begin(), jobs.end(),
                                  [&](const SceneJob& j) { return j.scene.name == scene; });
    if (job != jobs.end() && job->edgeMask.size() == e.reference.pixelCount())
        mask = &job->edgeMask;
    if (job == jobs.end()) {
        const std::string stem = "references/" + scene;
        writeImage((ctx.options.dir / (stem + ".exr")).string(), e.reference);
        writeImage((ctx.options.dir / (stem + ".png")).string(), e.reference, exposure);
        ctx.store.putReference({scene, e.renders.spec->name, 0, 0, "", 0, 0, exposure,
                                stem + ".exr", std::nullopt, std::nullopt, std::nullopt});
    }
    const CellMeter meter(e.reference, exposure, ctx.spec, mask);
    measureExternal(
        e,
        {scene, e.reference, exposure, meter, double(e.reference.pixelCount()) * kCellOverheadSpp},
        ctx);
}

// Every [[external]] table's images, and the references they name, read
// before anything is written: a bad table stops the study untouched.
std::vector<ExternalJob> findExternals(const StudySpec& spec) {
    std::vector<ExternalJob> out;
    for (const ExternalSpec& e : spec.externals) {
        ExternalJob job{findExternalImages(e), {}};
        if (!e.reference.empty()) job.reference = readImage(e.reference);
        checkExternalImageSizes(
            job.renders, e.reference.empty() ? spec.resolution
                                             : Vec2i{job.reference.width, job.reference.height});
        out.push_back(std::move(job));
    }
    return out;
}

int externalCellCount(const std::vector<ExternalJob>& externals) {
    int n = 0;
    for (const ExternalJob& e : externals) n += int(e.renders.images.size());
    return n;
}

std::vector<CellKey> unfinishedCells(const SceneJob& job, StudyContext& ctx) {
    std::vector<CellKey> todo;
    for (const CellKey& key : sceneCells(ctx.spec, job.scene.name)) {
        if (cellComplete(ctx.options.dir, ctx.store, key)) {
            ctx.progress.skipped(cellWork(ctx.spec, key));
            ++ctx.run.cellsSkipped;
        } else {
            todo.push_back(key);
        }
    }
    return todo;
}

void runScene(const SceneJob& job, StudyContext& ctx) {
    const std::vector<CellKey> todo = unfinishedCells(job, ctx);
    const Reference ref = obtainReference(job, ctx);
    recordReference(job, ref, ctx);
    const CellMeter meter(ref.image, ref.exposure, ctx.spec, &job.edgeMask);
    for (const CellRender& cells : planRenders(todo)) renderCells(job, ref, meter, cells, ctx);
    measureExternalsOfScene(job, ref, meter, ctx);
}

// All the study's work, in samples: every cell, and the references not yet
// in the cache. (Cells found done are subtracted as the run skips them.)
double totalWork(const StudySpec& spec, const std::vector<SceneJob>& jobs) {
    const ReferenceCache cache = ReferenceCache::standard();
    double work = 0;
    for (const SceneJob& job : jobs) {
        if (!cache.contains(job.cacheKey)) work += pixels(spec) * spec.reference.spp;
        for (const CellKey& key : sceneCells(spec, job.scene.name)) work += cellWork(spec, key);
    }
    return work;
}

void finishStudy(const StudySpec& spec, const StudyOptions& o, ResultsStore& store, StudyRun& run) {
    const std::vector<ReferenceRow> references = store.references();
    run.analysis = analyzeStudy(store.cells(), references, spec.timeBudgetSeconds);
    writeExports(o.dir, store, run.analysis);
    std::fprintf(stderr, "\n%s", summaryTable(run.analysis, references).c_str());
}

}  // namespace study_steps

using namespace study_steps;

void checkStudyOptions(const StudyOptions& options) {
    if (options.dir.empty()) throw InputError("-o/--output must name the study directory, got ''");
    std::error_code ec;
    if (fs::exists(options.dir, ec) && !fs::is_directory(options.dir, ec))
        throw InputError("'" + options.dir.string() +
                         "' is not a directory: -o/--output must name the study directory");
    if (options.threads < 0 || options.threads > kMaxStudyThreads)
        throw InputError("--threads must be between 0 (all cores) and " +
                         std::to_string(kMaxStudyThreads) + ", got " +
                         std::to_string(options.threads));
}

StudyRun runStudy(const StudySpec& spec, const StudyOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    // Everything that can be refused is refused before the directory is touched.
    checkStudyOptions(options);
    const std::vector<SceneJob> jobs = loadScenes(spec);
    const std::vector<ExternalJob> externals = findExternals(spec);
    checkDirectory(spec, jobs, options);
    const std::unique_ptr<ResultsStore> owned = beginStudyFiles(spec, jobs, options);
    ResultsStore& store = *owned;
    const int totalCells =
        int(spec.scenes.size() * spec.samplers.size() * spec.spp.size()) * spec.seeds +
        externalCellCount(externals);
    // External cells cost their metrics, counted at the study's size.
    StudyProgress progress(totalCells, totalWork(spec, jobs) + externalCellCount(externals) *
                                                                   pixels(spec) * kCellOverheadSpp);
    StudyRun run;
    StudyContext ctx{
        spec,     options, store,
        progress, run,     options.threads > 0 ? options.threads : tbb::info::default_concurrency(),
        externals};
    for (const SceneJob& job : jobs) runScene(job, ctx);
    for (const ExternalJob& e : externals)
        if (!e.renders.spec->reference.empty()) measureExternalWithReference(e, jobs, ctx);
    progress.finish();
    finishStudy(spec, options, store, run);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "study: %d cells rendered, %d already done, in %s; results in %s\n",
                 run.cellsRendered, run.cellsSkipped, formatDuration(run.seconds).c_str(),
                 options.dir.string().c_str());
    return run;
}

}  // namespace pathlab
