// Rank 0 of a study across MPI ranks: the dynamic schedule of cell renders.
// Every render waits in one list, largest first (Graham's LPT rule: the long
// renders start early, the short ones fill the gaps at the end); a rank that
// sends its results gets the next one. Rank 0 renders from the same list on a
// thread of its own, and alone commits rows to the results store.
#pragma once

#include <vector>

#include "study/mpi_messages.h"
#include "study/mpi_session.h"
#include "study/mpi_worker.h"
#include "study/runner_steps.h"

namespace pathlab {

// The renders that complete `todo` (each scene's unfinished cells), largest first.
std::vector<RenderTask> scheduleRenders(const StudySpec& spec,
                                        const std::vector<std::vector<CellKey>>& todo);

// Hands out `tasks` until all are done, committing each cell through `ctx`.
// Throws the first failure a rank reported, after every rank has stopped.
void coordinateRenders(const MpiSession& session, std::vector<RenderTask> tasks,
                       const std::vector<RankScene>& scenes, const study_steps::CellWriter& writer,
                       study_steps::StudyContext& ctx);

}  // namespace pathlab
