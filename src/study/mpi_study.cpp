#include "study/mpi_study.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>

#include "core/error.h"
#include "study/files.h"
#include "study/mpi_coordinator.h"
#include "study/mpi_messages.h"
#include "study/mpi_reference_ranges.h"
#include "study/mpi_worker.h"
#include "study/runner_steps.h"

namespace pathlab {
namespace {
using namespace study_steps;
namespace fs = std::filesystem;

// Runs `step` on this rank, then every rank learns whether one failed. The
// first rank that failed throws its error (so the job prints it once), the
// others stop quietly. Every rank must pass the same steps in the same order.
template <typename Step>
void collectively(const MpiSession& session, Step&& step) {
    std::exception_ptr error;
    try {
        step();
    } catch (...) {
        error = std::current_exception();
    }
    const int first = session.firstFailedRank(error != nullptr);
    if (first == session.rank()) std::rethrow_exception(error);
    if (first >= 0) throw StoppedWithAnotherRank();
}

// --threads per rank; by default the host's cores shared by its ranks.
int rankThreads(const StudyOptions& options, const MpiSession& session) {
    if (options.threads > 0) return options.threads;
    return std::max(1, tbb::info::default_concurrency() / session.ranksOnHost());
}

// A rank other than 0 must see the directory rank 0 prepared, and write to it.
void checkDirectoryReachable(const fs::path& dir, const MpiSession& session) {
    const std::string who = rankName(session.rank(), session.host());
    std::error_code ec;
    if (!fs::is_regular_file(dir / "spec.toml", ec))
        throw InputError(who + " cannot reach the study directory '" + dir.string() +
                         "' (no spec.toml there): it must be on a file system every host shares");
    const fs::path probe = dir / ("rank-" + std::to_string(session.rank()) + ".probe");
    try {
        writeTextFileAtomic(probe, session.host() + "\n");
    } catch (const InputError& e) {
        throw InputError(who + " cannot write to the study directory: " + e.what());
    }
    fs::remove(probe, ec);
}

// Rank 0's state for the whole run: the results store, the progress line.
struct Coordination {
    std::optional<DirectorySetup> setup;  // what the study directory held before
    std::unique_ptr<ResultsStore> store;
    std::optional<StudyProgress> progress;
    StudyRun run;
    std::optional<StudyContext> ctx;
    std::vector<std::vector<CellKey>> todo;  // per scene
};

void beginOnRankZero(const StudySpec& spec, const StudyOptions& options,
                     const std::vector<SceneJob>& jobs, const std::vector<ExternalJob>& externals,
                     int threads, Coordination& c) {
    checkDirectory(spec, jobs, options);
    c.setup.emplace(options.dir);
    c.store = beginStudyFiles(spec, jobs, options);
    const int totalCells =
        int(spec.scenes.size() * spec.samplers.size() * spec.spp.size()) * spec.seeds +
        externalCellCount(externals);
    c.progress.emplace(totalCells, totalWork(spec, jobs) + externalCellCount(externals) *
                                                               pixels(spec) * kCellOverheadSpp);
    c.ctx.emplace(StudyContext{spec, options, *c.store, *c.progress, c.run, threads, externals});
}

// Rank 0 takes each scene's reference from the cache or DIR, if it can; the
// sample ranges of the others not yet saved are rendered by all the ranks
// (mpi_reference_ranges.h), then merged by rank 0; every rank then receives
// each reference.
void shareReferences(const MpiSession& session, const StudySpec& spec,
                     const std::vector<SceneJob>& jobs, int threads, Coordination& c,
                     std::vector<RankScene>& scenes) {
    std::vector<std::optional<Reference>> found(jobs.size());
    std::vector<RangeTask> ranges;
    collectively(session, [&] {
        if (session.rank() != 0) return;
        for (size_t s = 0; s < jobs.size(); ++s) {
            c.todo.push_back(unfinishedCells(jobs[s], *c.ctx));
            found[s] = findReference(jobs[s], *c.ctx);
            if (!found[s])
                for (int index : missingReferenceRanges(jobs[s], *c.ctx))
                    ranges.push_back({int(s), index});
        }
    });
    collectively(session, [&] {
        if (session.rank() == 0)
            coordinateReferenceRanges(session, std::move(ranges), jobs, threads, *c.ctx);
        else
            renderReferenceRangesAsWorker(session, jobs, spec, threads);
    });
    std::vector<Reference> references(jobs.size());
    collectively(session, [&] {
        if (session.rank() != 0) return;
        for (size_t s = 0; s < jobs.size(); ++s) {
            references[s] = found[s] ? std::move(*found[s]) : finishReference(jobs[s], *c.ctx);
            recordReference(jobs[s], references[s], *c.ctx);
        }
    });
    for (size_t s = 0; s < jobs.size(); ++s) {
        std::vector<char> bytes;
        if (session.rank() == 0)
            bytes = encodeReferenceImage(references[s].image, references[s].exposure);
        session.broadcast(bytes);
        if (session.rank() != 0)
            decodeReferenceImage(bytes, references[s].image, references[s].exposure);
        scenes[s].reference = std::move(references[s]);
    }
}

void finishOnRankZero(const StudySpec& spec, const StudyOptions& options,
                      const std::vector<SceneJob>& jobs, const std::vector<ExternalJob>& externals,
                      const std::vector<RankScene>& scenes, Coordination& c) {
    for (size_t s = 0; s < jobs.size(); ++s)
        measureExternalsOfScene(jobs[s], scenes[s].reference, *scenes[s].meter, *c.ctx);
    for (const ExternalJob& e : externals)
        if (!e.renders.spec->reference.empty()) measureExternalWithReference(e, jobs, *c.ctx);
    c.progress->finish();
    finishStudy(spec, options, *c.store, c.run);
}

}  // namespace

StudyRun runStudyAcrossRanks(const std::function<StudySpec()>& loadSpec,
                             const StudyOptions& options, const MpiSession& session) {
    const auto start = std::chrono::steady_clock::now();
    const bool coordinator = session.rank() == 0;
    const int threads = rankThreads(options, session);
    std::vector<SceneJob> jobs;
    std::vector<ExternalJob> externals;
    Coordination c;
    StudySpec spec;
    collectively(session, [&] {
        checkStudyOptions(options);
        spec = loadSpec();
        jobs = loadScenes(spec);
        if (coordinator) externals = findExternals(spec);
    });
    collectively(session, [&] {
        if (coordinator) beginOnRankZero(spec, options, jobs, externals, threads, c);
    });
    try {
        collectively(session, [&] {
            if (!coordinator) checkDirectoryReachable(options.dir, session);
        });
    } catch (...) {
        // Nothing was rendered: the directory is left as it was, so the same
        // command works once every host reaches it.
        if (coordinator) {
            c.store.reset();
            c.setup->undo();
        }
        throw;
    }
    // Each rank renders with its share of its host's cores.
    std::optional<tbb::global_control> limit;
    limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
    std::vector<RankScene> scenes(jobs.size());
    shareReferences(session, spec, jobs, threads, c, scenes);
    for (size_t s = 0; s < jobs.size(); ++s) {
        scenes[s].job = &jobs[s];
        scenes[s].meter = std::make_unique<CellMeter>(
            scenes[s].reference.image, scenes[s].reference.exposure, spec, &jobs[s].edgeMask);
    }
    const CellWriter writer{spec, options.dir, threads};
    collectively(session, [&] {
        if (coordinator)
            coordinateRenders(session, scheduleRenders(spec, c.todo), scenes, writer, *c.ctx);
        else
            runStudyWorker(session, scenes, writer);
    });
    limit.reset();
    collectively(session, [&] {
        if (coordinator) finishOnRankZero(spec, options, jobs, externals, scenes, c);
    });
    if (!coordinator) return {};
    c.run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr,
                 "study: %d cells rendered, %d already done, in %s on %d ranks; results in %s\n",
                 c.run.cellsRendered, c.run.cellsSkipped, formatDuration(c.run.seconds).c_str(),
                 session.size(), options.dir.string().c_str());
    return std::move(c.run);
}

}  // namespace pathlab
