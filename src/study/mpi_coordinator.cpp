#include "study/mpi_coordinator.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "core/error.h"
#include "study/mpi_in_flight.h"
#include "study/mpi_work_queue.h"

namespace pathlab {
namespace {
using namespace study_steps;

double renderWork(const StudySpec& spec, const CellRender& render) {
    double work = 0;
    for (const CellKey& key : render.cells) work += cellWork(spec, key);
    return work;
}

using RenderQueue = WorkQueue<RenderTask, std::vector<MeasuredCell>>;

// "wolf halton-rd 1…256 spp seed 2 (9 cells)"
std::string renderLabel(const RenderTask& task) {
    const CellRender& r = task.cells;
    std::string spp = std::to_string(r.spp.front());
    if (r.spp.size() > 1) spp += "…" + std::to_string(r.spp.back());
    return r.cells.front().scene + " " + r.sampler + " " + spp + " spp seed " +
           std::to_string(r.seed) + " (" + std::to_string(r.cells.size()) + " cells)";
}

// Rank 0's own renders, on the thread that runs this.
void renderOnRankZero(RenderQueue& queue, const std::vector<RankScene>& scenes,
                      const CellWriter& writer) {
    renderQueueOnRankZero(
        queue, renderLabel, [](const RenderTask& t) { return cellLabel(t.cells.cells.front()); },
        [&](const RenderTask& t) {
            const RankScene& scene = scenes.at(size_t(t.scene));
            return renderCellGroup(*scene.job, scene.reference, *scene.meter, t.cells, writer);
        });
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
    std::string localShown;
    const auto commitLocal = [&] {
        for (const std::vector<MeasuredCell>& cells : queue.takeLocalResults())
            for (const MeasuredCell& cell : cells) commitCell(cell, ctx);
        // Rank 0's own render too, for the message a signal prints.
        if (std::string label = queue.localLabel(); label != localShown)
            inFlight.set(0, localShown = std::move(label));
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
