#include "study/files.h"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <ctime>
#include <memory>

#include "core/error.h"

namespace pathlab {
namespace fs = std::filesystem;

void writeTextFileAtomic(const fs::path& path, const std::string& content) {
    std::string name = ".";
    name += path.filename().string();
    name += ".tmp.";
    name += std::to_string(getpid());
    const fs::path tmp = path.parent_path() / name;
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) throw InputError("cannot write '" + path.string() + "'");
    size_t done = 0;
    bool ok = true;
    while (ok && done < content.size()) {
        const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
        ok = n > 0;
        if (ok) done += size_t(n);
    }
    ok = ::fsync(fd) == 0 && ok;
    ok = ::close(fd) == 0 && ok;
    std::error_code ec;
    if (ok) fs::rename(tmp, path, ec);
    if (!ok || ec) {
        fs::remove(tmp, ec);
        throw InputError("cannot write '" + path.string() + "'");
    }
}

const std::string& sourceGitCommit() {
    static const std::string commit = [] {
#ifdef PATHLAB_SOURCE_DIR
        const std::string cmd =
            std::string("git -C '") + PATHLAB_SOURCE_DIR + "' rev-parse HEAD 2>/dev/null";
        std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(cmd.c_str(), "r"), ::pclose);
        if (pipe) {
            char buffer[128] = {};
            if (std::fgets(buffer, sizeof buffer, pipe.get())) {
                std::string s(buffer);
                while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
                    s.pop_back();
                if (s.size() == 40) return s;
            }
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
