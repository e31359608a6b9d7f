#include "study/mpi_session.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <thread>

namespace pathlab {

bool launchedByMpiLauncher() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(name)) return true;
    return false;
}

MpiSession::MpiSession() {
    int provided = 0;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
        throw std::runtime_error("MPI_Init_thread failed");
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm local;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local);
    MPI_Comm_size(local, &ranksOnHost_);
    MPI_Comm_free(&local);
    char name[MPI_MAX_PROCESSOR_NAME] = {};
    int length = 0;
    MPI_Get_processor_name(name, &length);
    host_.assign(name, size_t(length));
}

MpiSession::~MpiSession() {
    MPI_Finalize();
}

int MpiSession::firstFailedRank(bool failed) const {
    int mine = failed ? rank_ : size_, first = size_;
    MPI_Request request;
    MPI_Iallreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &request);
    waitWithoutSpinning(&request);
    return first < size_ ? first : -1;
}

void MpiSession::broadcast(std::vector<char>& bytes) const {
    uint64_t size = bytes.size();
    MPI_Request request;
    MPI_Ibcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
    waitWithoutSpinning(&request);
    bytes.resize(size);
    // MPI counts are int: large payloads go in pieces.
    constexpr uint64_t kPiece = uint64_t(1) << 30;
    for (uint64_t at = 0; at < size; at += kPiece) {
        MPI_Ibcast(bytes.data() + at, int(std::min(kPiece, size - at)), MPI_CHAR, 0, MPI_COMM_WORLD,
                   &request);
        waitWithoutSpinning(&request);
    }
}

void waitWithoutSpinning(void* request) {
    auto* r = static_cast<MPI_Request*>(request);
    int done = 0;
    for (MPI_Test(r, &done, MPI_STATUS_IGNORE); !done; MPI_Test(r, &done, MPI_STATUS_IGNORE))
        std::this_thread::sleep_for(std::chrono::microseconds(200));
}

}  // namespace pathlab
