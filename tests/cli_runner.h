// Runs the pathlab executable from a test and captures what it says.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pathlab::testing {

struct CliResult {
    int exitCode = -1;
    std::string out, err;
    int errLines() const {
        int n = 0;
        for (char c : err) n += c == '\n';
        return n;
    }
};

inline std::string slurpFile(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// A fresh, empty scratch directory per test under the system temp directory.
inline std::filesystem::path scratchDirectory(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("pathlab-test-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// `pathlab ARGS`, with stdout and stderr captured through files in `dir`.
inline CliResult runPathlab(const std::string& args, const std::filesystem::path& dir) {
    const auto out = dir / "cli-stdout.txt", err = dir / "cli-stderr.txt";
    const std::string cmd = std::string(PATHLAB_BINARY) + " " + args + " >" + out.string() + " 2>" +
                            err.string() + " </dev/null";
    const int status = std::system(cmd.c_str());
    CliResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurpFile(out);
    r.err = slurpFile(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

}  // namespace pathlab::testing
