// The study's progress line on stderr: cells done of all, elapsed time and an
// ETA. Rewritten in place on a terminal; on a pipe or file, one line at most
// every few seconds, so logs stay readable.
#pragma once

#include <chrono>
#include <string>

namespace pathlab {

class StudyProgress {
  public:
    // `totalWork` is in samples (pixels × spp, plus a per-cell overhead):
    // cells cost in proportion to their spp, so counting cells would make
    // the ETA far too hopeful while the cheap low-spp cells run.
    StudyProgress(int totalCells, double totalWork);

    void skipped(double work);  // a cell already in the results
    void rendered(const std::string& what, double work);
    void addWorkDone(double work);          // e.g. a reference rendered
    void message(const std::string& line);  // a whole line, above the progress line
    void finish();

    int done() const { return done_; }

  private:
    void print(const std::string& what, bool force);
    double elapsed() const;

    int total_, done_ = 0;
    double totalWork_, workDone_ = 0, workSkipped_ = 0;
    std::chrono::steady_clock::time_point start_, lastPrint_;
    bool terminal_, lineOpen_ = false;
};

// "1h02m", "3m07s", "12.3s".
std::string formatDuration(double seconds);

}  // namespace pathlab
