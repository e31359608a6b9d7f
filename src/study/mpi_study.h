// `mpirun -np N pathlab study SPEC -o DIR [--resume]`: one study across N MPI
// ranks sharing DIR's file system (docs/cluster.md). Rank 0 checks and owns
// DIR's results store and the reference cache, renders the references, then
// hands out cell renders to the ranks as they become free, largest first, and
// commits what they send back; it renders cells itself on a thread of its
// own. The cells, images and metrics are those of the single-process study.
#pragma once

#include <exception>
#include <functional>

#include "study/mpi_session.h"
#include "study/runner.h"

namespace pathlab {

// What a rank throws when another rank failed and reports why. That rank
// alone exits with an error, so the job says it once: a rank that exited with
// an error first would make mpirun end the job before the report is printed.
struct StoppedWithAnotherRank : std::exception {
    const char* what() const noexcept override { return "stopped: another rank failed"; }
};

// Every rank calls it; rank 0's StudyRun is the study's, the others' are
// empty. Every rank reads the spec with `loadSpec`; a spec every rank finds
// wrong is reported by rank 0 alone.
StudyRun runStudyAcrossRanks(const std::function<StudySpec()>& loadSpec,
                             const StudyOptions& options, const MpiSession& session);

}  // namespace pathlab
