// The MPI side of `pathlab study` on a cluster (docs/cluster.md): whether this
// process was started by mpirun or srun, and the MPI session of one rank.
// MPI is initialised only when a launcher started the process, so a plain
// `pathlab study` never needs MPI_Init to succeed.
#pragma once

#include <string>
#include <vector>

namespace pathlab {

// True when an MPI launcher started this process: Open MPI's mpirun sets
// OMPI_COMM_WORLD_SIZE, Slurm's srun (PMI-2 or PMIx) sets PMI_SIZE or
// PMIX_RANK.
bool launchedByMpiLauncher();

// MPI_Init_thread (funneled: only the thread that made the session calls MPI)
// on construction, MPI_Finalize on destruction. One per process.
class MpiSession {
  public:
    MpiSession();
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }
    // The ranks on this rank's host (MPI_COMM_TYPE_SHARED): they share its cores.
    int ranksOnHost() const { return ranksOnHost_; }
    const std::string& host() const { return host_; }

    // The smallest rank for which `failed` is true, or -1 when none: every
    // rank must call it at the same point (MPI_Allreduce).
    int firstFailedRank(bool failed) const;
    // Rank 0's `bytes` on every rank, waiting without spinning (MPI_Ibcast).
    void broadcast(std::vector<char>& bytes) const;

  private:
    int rank_ = 0, size_ = 1, ranksOnHost_ = 1;
    std::string host_;
};

// Waits for a nonblocking MPI request by polling with short sleeps: a rank
// that waits in a blocking call spins on its core, which on a shared host
// takes it from the ranks that render.
void waitWithoutSpinning(void* request);

}  // namespace pathlab
