// A rank other than 0 in a study across MPI ranks: asks rank 0 for renders,
// renders and measures each, writes its cell images (atomically, into the
// shared study directory) and sends the measurements back.
#pragma once

#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "study/mpi_session.h"
#include "study/runner_steps.h"

namespace pathlab {

// One scene as every rank holds it: the scene, its reference and the meter.
struct RankScene {
    const study_steps::SceneJob* job = nullptr;
    Reference reference;
    std::unique_ptr<CellMeter> meter;
};

// Until rank 0 says stop. A render that fails is reported to rank 0, which
// ends the study with that message.
void runStudyWorker(const MpiSession& session, const std::vector<RankScene>& scenes,
                    const study_steps::CellWriter& writer);

// "rank 3 (node17)": how a message names a rank.
std::string rankName(int rank, const std::string& host);

// Receives the next message from `source` (any tag), waiting without
// spinning; returns its tag, and `from` the rank it came from.
int receiveMessage(int source, std::vector<char>& bytes, int& from);
void sendMessage(int to, int tag, const std::vector<char>& bytes);
// Whether a message from any rank is waiting to be received.
bool messageWaiting();

// The FAILED message of a rank whose work on `what` threw `error`: its first
// byte 'I' for the user's input (InputError), else 'E', then the line.
std::vector<char> failureMessage(const MpiSession& session, const std::string& what,
                                 const std::exception& error);
// The error a FAILED message carries, as rank 0 rethrows it.
std::exception_ptr reportedFailure(const std::vector<char>& bytes);

}  // namespace pathlab
