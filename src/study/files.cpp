#include "study/files.h"

#include <cctype>
#include <cstdio>
#include <ctime>
#include <memory>

#include "core/atomic_file.h"

namespace pathlab {
namespace fs = std::filesystem;

void writeTextFileAtomic(const fs::path& path, const std::string& content) {
    writeFileAtomic(path.string(), content);
}

namespace {

// The first line `command` prints, without trailing white space ("" if none).
std::string firstLineOf(const std::string& command) {
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(command.c_str(), "r"), ::pclose);
    char buffer[128] = {};
    if (!pipe || !std::fgets(buffer, sizeof buffer, pipe.get())) return "";
    std::string s(buffer);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    return s;
}

}  // namespace

const std::string& sourceGitCommit() {
    static const std::string commit = [] {
#ifdef PATHLAB_SOURCE_DIR
        const std::string git = std::string("git -C '") + PATHLAB_SOURCE_DIR + "' ";
        const std::string head = firstLineOf(git + "rev-parse HEAD 2>/dev/null");
        if (head.size() == 40) {
            // A tree with changes to tracked files is not that commit.
            const bool dirty =
                !firstLineOf(git + "status --porcelain --untracked-files=no 2>/dev/null").empty();
            return dirty ? head + "-dirty" : head;
        }
#endif
        return std::string("unknown");
    }();
    return commit;
}

std::string isoTimestampUtc() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return buffer;
}

}  // namespace pathlab
