// The references of a study across MPI ranks, rendered by all the ranks: each
// missing sample range (reference_ranges.h) is handed out like a cell render,
// the longest first; the rank renders it with its threads and sends its sums
// to rank 0, which saves each as a range file (so a job killed now keeps it)
// and, once every range is in, merges them in range order — the same bits as
// one process makes, whatever the number of ranks.
#pragma once

#include <vector>

#include "study/mpi_messages.h"
#include "study/mpi_session.h"
#include "study/runner_steps.h"

namespace pathlab {

// Rank 0: hands out `ranges` until all are rendered and saved, rendering some
// on a thread of its own. Throws the first failure a rank reported, after
// every rank has stopped.
void coordinateReferenceRanges(const MpiSession& session, std::vector<RangeTask> ranges,
                               const std::vector<study_steps::SceneJob>& jobs, int threads,
                               study_steps::StudyContext& ctx);

// The other ranks: render the ranges rank 0 sends until it says stop.
void renderReferenceRangesAsWorker(const MpiSession& session,
                                   const std::vector<study_steps::SceneJob>& jobs,
                                   const StudySpec& spec, int threads);

}  // namespace pathlab
