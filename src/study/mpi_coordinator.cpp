#include "study/mpi_coordinator.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "core/error.h"
#include "study/mpi_in_flight.h"

namespace pathlab {
namespace {
using namespace study_steps;

double renderWork(const StudySpec& spec, const CellRender& render) {
    double work = 0;
    for (const CellKey& key : render.cells) work += cellWork(spec, key);
    return work;
}

// The list of renders, shared by the thread that talks to the ranks and the
// thread that renders on rank 0; and the results rank 0 rendered, waiting to
// be committed by the first (the results store has one writer).
class RenderQueue {
  public:
    explicit RenderQueue(std::vector<RenderTask> tasks) : tasks_(std::move(tasks)) {}

    std::optional<RenderTask> next() {
        std::lock_guard lock(mutex_);
        if (failure_ || next_ == tasks_.size()) return std::nullopt;
        return tasks_[next_++];
    }
    void fail(std::exception_ptr error) {
        std::lock_guard lock(mutex_);
        if (!failure_) failure_ = error;
    }
    std::exception_ptr failure() {
        std::lock_guard lock(mutex_);
        return failure_;
    }
    void addLocalResults(std::vector<MeasuredCell> cells) {
        std::lock_guard lock(mutex_);
        for (MeasuredCell& c : cells) local_.push_back(std::move(c));
    }
    std::vector<MeasuredCell> takeLocalResults() {
        std::lock_guard lock(mutex_);
        return std::exchange(local_, {});
    }

  private:
    std::mutex mutex_;
    std::vector<RenderTask> tasks_;
    size_t next_ = 0;
    std::exception_ptr failure_;
    std::vector<MeasuredCell> local_;
};

// Rank 0's own renders, on the thread that runs this.
void renderOnRankZero(RenderQueue& queue, const std::vector<RankScene>& scenes,
                      const CellWriter& writer) {
    while (const std::optional<RenderTask> task = queue.next()) {
        const RankScene& scene = scenes.at(size_t(task->scene));
        try {
            queue.addLocalResults(
                renderCellGroup(*scene.job, scene.reference, *scene.meter, task->cells, writer));
        } catch (const InputError& e) {
            queue.fail(std::make_exception_ptr(InputError(
                "rank 0, rendering " + cellLabel(task->cells.cells.front()) + ": " + e.what())));
        } catch (...) {
            queue.fail(std::current_exception());
        }
    }
}

std::exception_ptr reportedFailure(const std::vector<char>& bytes) {
    const std::string text(bytes.begin() + (bytes.empty() ? 0 : 1), bytes.end());
    if (!bytes.empty() && bytes[0] == 'I') return std::make_exception_ptr(InputError(text));
    return std::make_exception_ptr(std::runtime_error(text));
}

// "wolf halton-rd 1…256 spp seed 2 (9 cells)"
std::string renderLabel(const RenderTask& task) {
    const CellRender& r = task.cells;
    std::string spp = std::to_string(r.spp.front());
    if (r.spp.size() > 1) spp += "…" + std::to_string(r.spp.back());
    return r.cells.front().scene + " " + r.sampler + " " + spp + " spp seed " +
           std::to_string(r.seed) + " (" + std::to_string(r.cells.size()) + " cells)";
}

// One message of a worker: its results are committed, and it gets the next
// render or is told to stop. Returns false when it was told to stop.
bool answerWorker(int tag, int from, const std::vector<char>& bytes, RenderQueue& queue,
                  RendersInFlight& inFlight, StudyContext& ctx) {
    inFlight.set(from, "");
    if (tag == kTagResult)
        for (const MeasuredCell& cell : decodeMeasured(bytes)) commitCell(cell, ctx);
    if (tag == kTagFailed) queue.fail(reportedFailure(bytes));
    if (const std::optional<RenderTask> task = queue.next()) {
        inFlight.set(from, renderLabel(*task));
        sendMessage(from, kTagRender, encodeTask(*task));
        return true;
    }
    sendMessage(from, kTagStop, {});
    return false;
}

bool messageWaiting() {
    int arrived = 0;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, MPI_STATUS_IGNORE);
    return arrived != 0;
}

}  // namespace

std::vector<RenderTask> scheduleRenders(const StudySpec& spec,
                                        const std::vector<std::vector<CellKey>>& todo) {
    std::vector<RenderTask> tasks;
    for (size_t s = 0; s < todo.size(); ++s)
        for (CellRender& r : planRenders(todo[s])) tasks.push_back({int(s), std::move(r)});
    // Stable: renders of equal work keep the single-process order.
    std::stable_sort(tasks.begin(), tasks.end(), [&](const RenderTask& a, const RenderTask& b) {
        return renderWork(spec, a.cells) > renderWork(spec, b.cells);
    });
    return tasks;
}

void coordinateRenders(const MpiSession& session, std::vector<RenderTask> tasks,
                       const std::vector<RankScene>& scenes, const CellWriter& writer,
                       StudyContext& ctx) {
    RenderQueue queue(std::move(tasks));
    RendersInFlight inFlight(session.size());
    std::thread local([&] { renderOnRankZero(queue, scenes, writer); });
    int working = session.size() - 1;
    std::vector<char> bytes;
    const auto commitLocal = [&] {
        for (const MeasuredCell& cell : queue.takeLocalResults()) commitCell(cell, ctx);
    };
    while (working > 0) {
        commitLocal();
        if (!messageWaiting()) {
            std::this_thread::sleep_for(std::chrono::microseconds(200));
            continue;
        }
        int from = 0;
        const int tag = receiveMessage(MPI_ANY_SOURCE, bytes, from);
        if (!answerWorker(tag, from, bytes, queue, inFlight, ctx)) --working;
    }
    local.join();
    commitLocal();
    if (const std::exception_ptr failure = queue.failure()) std::rethrow_exception(failure);
}

}  // namespace pathlab
