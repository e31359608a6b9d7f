#include "report/report_writer.h"

#include <fcntl.h>
#include <spawn.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

extern char** environ;

namespace pathlab {
namespace fs = std::filesystem;

namespace {

// Runs argv[0] (searched on PATH) with the given arguments, optionally with its
// stdout and stderr discarded; returns its exit code, or -1 if it could not run.
int runProgram(const std::vector<std::string>& args, bool quiet) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (quiet) {
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    }
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return -1;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return -1;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s;
}

// Counts the finished cells, or returns -1 when the database has no cells table.
long long countCells(const fs::path& database) {
    sqlite3* db = nullptr;
    // Read-write without create: a read-only handle cannot open a WAL database
    // whose -shm file is missing, and nothing here writes.
    if (sqlite3_open_v2(database.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
        sqlite3_close(db);
        return -1;
    }
    sqlite3_busy_timeout(db, 5000);
    sqlite3_stmt* stmt = nullptr;
    long long count = -1;
    if (sqlite3_prepare_v2(db, "SELECT count(*) FROM cells", -1, &stmt, nullptr) == SQLITE_OK &&
        sqlite3_step(stmt) == SQLITE_ROW)
        count = sqlite3_column_int64(stmt, 0);
    sqlite3_finalize(stmt);
    sqlite3_close(db);
    return count;
}

}  // namespace

void requireStudyDirectory(const fs::path& dir) {
    const std::string name = dir.string();
    if (!fs::is_directory(dir)) throw InputError("'" + name + "' is not a directory");
    const fs::path database = dir / "results.sqlite";
    if (!fs::is_regular_file(database))
        throw InputError("'" + name + "' is not a study directory (no results.sqlite)");
    // The report is built beside DIR/report and renamed into place, and the
    // database is opened read-write (see countCells): both need DIR writable,
    // which is worth saying as such rather than as a database that fails.
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
        throw InputError(writeErrorMessage((dir / "report").string(), errno));
    std::error_code ec;
    const fs::path report = dir / "report";
    if (fs::exists(fs::symlink_status(report, ec)) && !fs::is_directory(report, ec))
        throw InputError("'" + report.string() +
                         "' is not a directory: move it away, the report is written there");
    const long long cells = countCells(database);
    if (cells < 0)
        throw InputError("'" + database.string() + "' is not a study database (no cells table)");
    if (cells == 0) throw InputError("'" + name + "' has no finished cells yet");
}

fs::path reportAssetsDirectory() {
    if (const char* env = std::getenv("PATHLAB_REPORT_ASSETS"); env && *env) return env;
    return fs::path(PATHLAB_SOURCE_DIR) / "src" / "report";
}

std::string findPython() {
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("PATHLAB_PYTHON"); env && *env) candidates.push_back(env);
    candidates.push_back("python3");
    candidates.push_back("/usr/bin/python3");
    for (const std::string& python : candidates)
        if (runProgram({python, "-c", "import matplotlib, numpy"}, true) == 0) return python;
    throw std::runtime_error(
        "no python3 with matplotlib and numpy found (install python3-matplotlib and "
        "python3-numpy, e.g. with scripts/setup.sh, or set PATHLAB_PYTHON)");
}

fs::path writeReport(const ReportOptions& options) {
    requireStudyDirectory(options.studyDir);
    const fs::path script = reportAssetsDirectory() / "make_report.py";
    if (!fs::is_regular_file(script))
        throw std::runtime_error("report script '" + script.string() +
                                 "' not found (set PATHLAB_REPORT_ASSETS to src/report)");
    const std::string python = findPython();
    // The script leaves a bad-input message here, so it reaches the user as one
    // line through the usual InputError path.
    const fs::path errorFile =
        fs::temp_directory_path() / ("pathlab-report-" + std::to_string(::getpid()) + ".err");
    std::vector<std::string> args = {python,
                                     "-B",  // no __pycache__ in the source tree
                                     script.string(),
                                     options.studyDir.string(),
                                     "--error-file",
                                     errorFile.string()};
    if (!options.pathlabBinary.empty()) {
        args.push_back("--pathlab");
        args.push_back(options.pathlabBinary.string());
    }
    const int rc = runProgram(args, false);
    const std::string message = fs::exists(errorFile) ? readFile(errorFile) : "";
    std::error_code ec;
    fs::remove(errorFile, ec);
    if (rc == 2 && !message.empty()) throw InputError(message);
    if (rc != 0)
        throw std::runtime_error("the report script failed (" + python + " " + script.string() +
                                 ", exit code " + std::to_string(rc) + ")");
    return options.studyDir / "report" / "index.html";
}

}  // namespace pathlab
