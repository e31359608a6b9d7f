// Rank 0's list of work in a study across MPI ranks (cell renders, sample
// ranges of references), shared by the thread that talks to the ranks and
// the thread that renders on rank 0 itself; and what rank 0 rendered, waiting
// for the first thread, which alone writes results.
#pragma once

#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"

namespace pathlab {

template <typename Task, typename Result>
class WorkQueue {
  public:
    explicit WorkQueue(std::vector<Task> tasks) : tasks_(std::move(tasks)) {}

    // The next task for another rank; nullopt once all are out or one failed.
    std::optional<Task> next() {
        std::lock_guard lock(mutex_);
        return nextLocked();
    }
    // The next task for rank 0's own thread, in flight under `label` until
    // its result is added (or the thread fails).
    template <typename LabelOf>
    std::optional<Task> nextLocal(const LabelOf& labelOf) {
        std::lock_guard lock(mutex_);
        std::optional<Task> task = nextLocked();
        localLabel_ = task ? labelOf(*task) : "";
        return task;
    }
    void addLocalResult(Result result) {
        std::lock_guard lock(mutex_);
        local_.push_back(std::move(result));
        localLabel_.clear();
    }
    std::vector<Result> takeLocalResults() {
        std::lock_guard lock(mutex_);
        return std::exchange(local_, {});
    }
    // What rank 0's own thread renders now ("" when nothing).
    std::string localLabel() {
        std::lock_guard lock(mutex_);
        return localLabel_;
    }
    void fail(std::exception_ptr error) {
        std::lock_guard lock(mutex_);
        if (!failure_) failure_ = error;
        localLabel_.clear();
    }
    std::exception_ptr failure() {
        std::lock_guard lock(mutex_);
        return failure_;
    }

  private:
    std::optional<Task> nextLocked() {
        if (failure_ || next_ == tasks_.size()) return std::nullopt;
        return tasks_[next_++];
    }
    std::mutex mutex_;
    std::vector<Task> tasks_;
    size_t next_ = 0;
    std::exception_ptr failure_;
    std::vector<Result> local_;
    std::string localLabel_;
};

// Rank 0's own thread: takes tasks from `queue` until none is left (or one
// failed), rendering each with `render` and adding its result. A failure ends
// the queue; the user's input errors are named "rank 0, rendering WHAT: …"
// with `what` of the task, as other ranks name theirs (failureMessage).
template <typename Task, typename Result, typename LabelOf, typename WhatOf, typename Render>
void renderQueueOnRankZero(WorkQueue<Task, Result>& queue, const LabelOf& labelOf,
                           const WhatOf& whatOf, const Render& render) {
    while (const std::optional<Task> task = queue.nextLocal(labelOf)) {
        try {
            queue.addLocalResult(render(*task));
        } catch (const InputError& e) {
            queue.fail(std::make_exception_ptr(
                InputError("rank 0, rendering " + whatOf(*task) + ": " + e.what())));
        } catch (...) {
            queue.fail(std::current_exception());
        }
    }
}

}  // namespace pathlab
