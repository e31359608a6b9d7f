#include "core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace pathlab {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kTemporaryInfix = ".tmp.";

// The PID of a temporary's name, or -1 when `name` is not one.
long temporaryOwner(const std::string& name) {
    if (name.size() < 2 || name[0] != '.') return -1;
    const size_t at = name.rfind(kTemporaryInfix);
    if (at == std::string::npos || at == 0) return -1;
    const std::string digits = name.substr(at + kTemporaryInfix.size());
    if (digits.empty() || digits.size() > 9 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
        return -1;
    return std::stol(digits);
}

// Flushes the directory holding `path`, so the rename itself is durable.
void syncDirectoryOf(const std::string& path) {
    const fs::path dir = fs::path(path).parent_path();
    const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (fd < 0) return;
    ::fsync(fd);  // best effort: some file systems refuse fsync on directories
    ::close(fd);
}

}  // namespace

std::string writeErrorMessage(const std::string& path, int error) {
    switch (error) {
        case ENOSPC:
            return "no space left on device writing '" + path + "'";
        case EDQUOT:
            return "disk quota exceeded writing '" + path + "'";
        case EFBIG:
            return "file too large writing '" + path + "'";
        case EROFS:
            return "cannot write '" + path + "': read-only file system";
        default:
            return "cannot write '" + path + "': " + std::strerror(error);
    }
}

std::string temporaryPathFor(const std::string& path) {
    const fs::path p(path);
    std::string name = ".";  // appended piecewise: GCC 12 misreports "." + string (-Wrestrict)
    name += p.filename().string();
    name += kTemporaryInfix;
    name += std::to_string(getpid());
    return (p.parent_path() / name).string();
}

bool isTemporaryName(const std::string& name) {
    return temporaryOwner(name) >= 0;
}

void writeFileAtomic(const std::string& path, std::string_view bytes) {
    const std::string tmp = temporaryPathFor(path);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw InputError(writeErrorMessage(path, errno));
    int error = 0;
    size_t done = 0;
    while (error == 0 && done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n > 0)
            done += size_t(n);
        else if (n < 0 && errno != EINTR)
            error = errno;
        else if (n == 0)
            error = EIO;
    }
    // Data on disk before the name: after a crash the name shows the old
    // file or the whole new one.
    if (error == 0 && ::fsync(fd) != 0) error = errno;
    if (::close(fd) != 0 && error == 0) error = errno;
    if (error == 0 && ::rename(tmp.c_str(), path.c_str()) != 0) error = errno;
    if (error != 0) {
        ::unlink(tmp.c_str());
        throw InputError(writeErrorMessage(path, error));
    }
    syncDirectoryOf(path);
}

int removeStaleTemporaries(const fs::path& dir) {
    int removed = 0;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(dir, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        const long owner = temporaryOwner(it->path().filename().string());
        if (owner < 0 || !it->is_regular_file(ec)) continue;
        // A live owner (this process, or another one writing here) keeps its file.
        if (owner == long(getpid()) || ::kill(pid_t(owner), 0) == 0 || errno != ESRCH) continue;
        std::error_code removeError;
        if (fs::remove(it->path(), removeError)) ++removed;
    }
    return removed;
}

}  // namespace pathlab
