#include "study/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pathlab {

std::string formatDuration(double seconds) {
    char buffer[32];
    if (!std::isfinite(seconds) || seconds < 0) return "?";
    if (seconds < 60) {
        std::snprintf(buffer, sizeof buffer, "%.1fs", seconds);
    } else if (seconds < 3600) {
        const int s = int(std::lround(seconds));
        std::snprintf(buffer, sizeof buffer, "%dm%02ds", s / 60, s % 60);
    } else {
        const int m = int(std::lround(seconds / 60));
        std::snprintf(buffer, sizeof buffer, "%dh%02dm", m / 60, m % 60);
    }
    return buffer;
}

StudyProgress::StudyProgress(int totalCells, double totalWork)
    : total_(totalCells),
      totalWork_(totalWork),
      start_(std::chrono::steady_clock::now()),
      lastPrint_(start_),
      terminal_(::isatty(STDERR_FILENO) == 1) {}

double StudyProgress::elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void StudyProgress::skipped(double work) {
    ++done_;
    workSkipped_ += work;
}

void StudyProgress::addWorkDone(double work) {
    workDone_ += work;
}

void StudyProgress::rendered(const std::string& what, double work) {
    ++done_;
    workDone_ += work;
    print(what, done_ == total_);
}

void StudyProgress::message(const std::string& line) {
    if (lineOpen_) std::fputs("\n", stderr);
    lineOpen_ = false;
    std::fprintf(stderr, "%s\n", line.c_str());
}

void StudyProgress::print(const std::string& what, bool force) {
    const auto now = std::chrono::steady_clock::now();
    const double sinceLast = std::chrono::duration<double>(now - lastPrint_).count();
    if (!force && sinceLast < (terminal_ ? 0.2 : 5.0)) return;
    lastPrint_ = now;
    const double t = elapsed();
    const double remaining = totalWork_ - workDone_ - workSkipped_;
    const double eta = workDone_ > 0 ? t / workDone_ * std::max(remaining, 0.0) : NAN;
    char line[256];
    std::snprintf(line, sizeof line, "[%d/%d cells] %s | elapsed %s, ETA %s", done_, total_,
                  what.c_str(), formatDuration(t).c_str(), formatDuration(eta).c_str());
    if (terminal_) {
        std::fprintf(stderr, "\r%s\033[K", line);
        lineOpen_ = true;
    } else {
        std::fprintf(stderr, "%s\n", line);
    }
    std::fflush(stderr);
}

void StudyProgress::finish() {
    if (lineOpen_) std::fputs("\n", stderr);
    lineOpen_ = false;
}

}  // namespace pathlab
