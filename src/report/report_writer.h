// `pathlab report`: turns a study directory into DIR/report/ — index.html, the
// figures as SVG and PNG, and the images the page shows. The page and figures
// are made by src/report/make_report.py (matplotlib); this side checks the
// input, finds Python and the scripts, and runs them.
#pragma once

#include <filesystem>
#include <string>

namespace pathlab {

struct ReportOptions {
    std::filesystem::path studyDir;
    // The pathlab binary, run for the sampler gallery (`pathlab points`).
    std::filesystem::path pathlabBinary;
};

// Throws InputError unless `dir` holds a study with at least one finished cell.
void requireStudyDirectory(const std::filesystem::path& dir);

// The directory holding make_report.py, template.html and comparer.js:
// $PATHLAB_REPORT_ASSETS if set, else src/report of the source tree.
std::filesystem::path reportAssetsDirectory();

// A Python 3 interpreter that can import matplotlib and numpy: $PATHLAB_PYTHON,
// else python3 on PATH, else /usr/bin/python3 (where Debian's packages live).
// Throws std::runtime_error when there is none.
std::string findPython();

// Writes STUDY/report/ and returns the path of its index.html. Throws
// InputError for a directory that is not a study, std::runtime_error for an
// internal failure.
std::filesystem::path writeReport(const ReportOptions& options);

}  // namespace pathlab
