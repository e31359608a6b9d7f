#include "study/mpi_reference_ranges.h"

#include <mpi.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "core/error.h"
#include "study/mpi_in_flight.h"
#include "study/mpi_work_queue.h"
#include "study/mpi_worker.h"

namespace pathlab {
namespace {
using namespace study_steps;

struct RenderedRange {
    int scene = 0;
    RangeSums sums;
};

using RangeQueue = WorkQueue<RangeTask, RenderedRange>;

std::vector<std::string> cacheKeys(const std::vector<SceneJob>& jobs) {
    std::vector<std::string> keys;
    for (const SceneJob& job : jobs) keys.push_back(job.cacheKey);
    return keys;
}

void renderRangesOnRankZero(RangeQueue& queue, const std::vector<SceneJob>& jobs,
                            const StudySpec& spec, int threads) {
    const auto label = [&](const RangeTask& t) {
        return rangeLabel(jobs.at(size_t(t.scene)), spec, t.index);
    };
    renderQueueOnRankZero(queue, label, label, [&](const RangeTask& t) {
        return RenderedRange{t.scene, renderReferenceRange(*jobs.at(size_t(t.scene)).render, spec,
                                                           threads, t.index)};
    });
}

}  // namespace

void coordinateReferenceRanges(const MpiSession& session, std::vector<RangeTask> ranges,
                               const std::vector<SceneJob>& jobs, int threads, StudyContext& ctx) {
    RangeQueue queue(std::move(ranges));
    RendersInFlight inFlight(session.size());
    const auto label = [&](const RangeTask& t) {
        return rangeLabel(jobs.at(size_t(t.scene)), ctx.spec, t.index);
    };
    const std::vector<std::string> keys = cacheKeys(jobs);
    // A range that cannot be saved (a full disk) ends the study once every
    // rank has stopped, as a failed render does.
    const auto save = [&](const RenderedRange& r) {
        try {
            saveReferenceRange(jobs.at(size_t(r.scene)), r.sums, ctx);
            ctx.progress.message("reference: rendered " + label({r.scene, r.sums.index}));
        } catch (...) {
            queue.fail(std::current_exception());
        }
    };
    std::thread local([&] { renderRangesOnRankZero(queue, jobs, ctx.spec, threads); });
    std::string localShown;
    const auto saveLocal = [&] {
        for (const RenderedRange& r : queue.takeLocalResults()) save(r);
        if (std::string l = queue.localLabel(); l != localShown)
            inFlight.set(0, localShown = std::move(l));
    };
    int working = session.size() - 1;
    std::vector<char> bytes;
    while (working > 0) {
        saveLocal();
        if (!messageWaiting()) {
            std::this_thread::sleep_for(std::chrono::microseconds(200));
            continue;
        }
        int from = 0;
        const int tag = receiveMessage(MPI_ANY_SOURCE, bytes, from);
        inFlight.set(from, "");
        if (tag == kTagSums) {
            RenderedRange r;
            try {
                r.sums = decodeRangeResult(bytes, r.scene, keys);
                save(r);
            } catch (...) {
                queue.fail(std::current_exception());
            }
        }
        if (tag == kTagFailed) queue.fail(reportedFailure(bytes));
        if (const std::optional<RangeTask> task = queue.next()) {
            inFlight.set(from, label(*task));
            sendMessage(from, kTagRange, encodeRangeTask(*task));
            continue;
        }
        sendMessage(from, kTagStop, {});
        --working;
    }
    local.join();
    saveLocal();
    if (const std::exception_ptr failure = queue.failure()) std::rethrow_exception(failure);
}

void renderReferenceRangesAsWorker(const MpiSession& session, const std::vector<SceneJob>& jobs,
                                   const StudySpec& spec, int threads) {
    sendMessage(0, kTagReady, {});
    std::vector<char> bytes;
    int from = 0;
    while (receiveMessage(0, bytes, from) == kTagRange) {
        const RangeTask task = decodeRangeTask(bytes);
        const SceneJob& job = jobs.at(size_t(task.scene));
        try {
            const RangeSums r = renderReferenceRange(*job.render, spec, threads, task.index);
            sendMessage(0, kTagSums, encodeRangeResult(task.scene, r, job.cacheKey));
        } catch (const std::exception& e) {
            sendMessage(0, kTagFailed,
                        failureMessage(session, rangeLabel(job, spec, task.index), e));
        }
    }
}

}  // namespace pathlab
