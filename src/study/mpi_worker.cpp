#include "study/mpi_worker.h"

#include <mpi.h>

#include <chrono>
#include <thread>

#include "core/error.h"
#include "study/mpi_messages.h"

namespace pathlab {

std::string rankName(int rank, const std::string& host) {
    return "rank " + std::to_string(rank) + " (" + host + ")";
}

int receiveMessage(int source, std::vector<char>& bytes, int& from) {
    MPI_Status status;
    int arrived = 0;
    for (MPI_Iprobe(source, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status); !arrived;
         MPI_Iprobe(source, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status))
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    int count = 0;
    MPI_Get_count(&status, MPI_CHAR, &count);
    bytes.resize(size_t(count));
    MPI_Recv(bytes.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    from = status.MPI_SOURCE;
    return status.MPI_TAG;
}

void sendMessage(int to, int tag, const std::vector<char>& bytes) {
    MPI_Send(bytes.data(), int(bytes.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD);
}

bool messageWaiting() {
    int arrived = 0;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, MPI_STATUS_IGNORE);
    return arrived != 0;
}

std::vector<char> failureMessage(const MpiSession& session, const std::string& what,
                                 const std::exception& error) {
    const bool input = dynamic_cast<const InputError*>(&error) != nullptr;
    const std::string text = std::string(input ? "I" : "E") +
                             rankName(session.rank(), session.host()) + ", rendering " + what +
                             ": " + error.what();
    return std::vector<char>(text.begin(), text.end());
}

std::exception_ptr reportedFailure(const std::vector<char>& bytes) {
    const std::string text =
        bytes.size() > 1 ? std::string(bytes.data() + 1, bytes.size() - 1) : std::string();
    if (!bytes.empty() && bytes[0] == 'I') return std::make_exception_ptr(InputError(text));
    return std::make_exception_ptr(std::runtime_error(text));
}

void runStudyWorker(const MpiSession& session, const std::vector<RankScene>& scenes,
                    const study_steps::CellWriter& writer) {
    sendMessage(0, kTagReady, {});
    std::vector<char> bytes;
    int from = 0;
    while (receiveMessage(0, bytes, from) == kTagRender) {
        const RenderTask task = decodeTask(bytes);
        const RankScene& scene = scenes.at(size_t(task.scene));
        try {
            const auto measured = study_steps::renderCellGroup(*scene.job, scene.reference,
                                                               *scene.meter, task.cells, writer);
            sendMessage(0, kTagResult, encodeMeasured(measured));
        } catch (const std::exception& e) {
            sendMessage(
                0, kTagFailed,
                failureMessage(session, study_steps::cellLabel(task.cells.cells.front()), e));
        }
    }
}

}  // namespace pathlab
