// Which cell each rank is rendering, for the one message a study across MPI
// ranks can still give when a rank dies: Open MPI's mpirun then says which
// rank died and ends the others with SIGTERM; rank 0's handler prints the
// renders that were in flight, so the job log names the rank and its cell.
#pragma once

#include <string>

namespace pathlab {

class RendersInFlight {
  public:
    // Installs the SIGTERM handler (once per process) for `ranks` ranks.
    explicit RendersInFlight(int ranks);
    ~RendersInFlight();  // restores the previous handler
    RendersInFlight(const RendersInFlight&) = delete;
    RendersInFlight& operator=(const RendersInFlight&) = delete;

    // `label` empty: the rank renders nothing now. Not thread-safe: one
    // thread (rank 0's, the one that talks to the ranks) calls it.
    void set(int rank, const std::string& label);

  private:
    void publish();
};

}  // namespace pathlab
