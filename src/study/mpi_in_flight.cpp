#include "study/mpi_in_flight.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <vector>

namespace pathlab {
namespace {

// The handler may only read memory that is never freed or resized while it
// is installed: two fixed buffers, the one published by an atomic pointer,
// the other rewritten (double buffering, so a handler never sees half a text).
struct InFlightText {
    std::vector<std::string> labels;
    std::vector<char> buffers[2];
    int current = 0;
    std::atomic<const char*> published{nullptr};
    struct sigaction previous {};
};
InFlightText* gText = nullptr;

// Per rank, at most this many bytes of its line.
constexpr size_t kLineBytes = 160;

void onTerminate(int signal) {
    if (const InFlightText* t = gText) {
        if (const char* text = t->published.load()) {
            const ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
            (void)ignored;
        }
    }
    ::signal(signal, SIG_DFL);
    ::raise(signal);
}

}  // namespace

RendersInFlight::RendersInFlight(int ranks) {
    gText = new InFlightText;
    gText->labels.resize(size_t(ranks));
    const size_t bytes = 200 + kLineBytes * size_t(ranks);
    gText->buffers[0].assign(bytes, '\0');
    gText->buffers[1].assign(bytes, '\0');
    struct sigaction action {};
    action.sa_handler = onTerminate;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGTERM, &action, &gText->previous);
}

RendersInFlight::~RendersInFlight() {
    ::sigaction(SIGTERM, &gText->previous, nullptr);
    delete gText;
    gText = nullptr;
}

void RendersInFlight::set(int rank, const std::string& label) {
    gText->labels.at(size_t(rank)) = label;
    publish();
}

void RendersInFlight::publish() {
    std::string text =
        "\npathlab: study stopped by a signal; renders in flight (not committed, "
        "--resume renders them again):\n";
    for (size_t r = 0; r < gText->labels.size(); ++r)
        if (!gText->labels[r].empty())
            text += ("  rank " + std::to_string(r) + ": " + gText->labels[r])
                        .substr(0, kLineBytes - 1) +
                    "\n";
    InFlightText& t = *gText;
    t.current = 1 - t.current;
    std::vector<char>& buffer = t.buffers[t.current];
    const size_t n = std::min(text.size(), buffer.size() - 1);
    std::memcpy(buffer.data(), text.data(), n);
    buffer[n] = '\0';
    t.published.store(buffer.data());
}

}  // namespace pathlab
