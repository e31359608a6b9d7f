// A small, size-limited file system for tests of a full disk: a tmpfs of a
// given size, mounted where the test can reach it. Ways tried, in order:
//   1. mount(2) directly — root with CAP_SYS_ADMIN (a CI machine, a VM);
//   2. the test process moves into a new user and mount namespace and mounts
//      it there — any user (root without CAP_SYS_ADMIN too) where user
//      namespaces are allowed; the test process stays in that namespace.
// When neither works, available() is false and why() says what failed, so
// the test can skip with the reason. PATHLAB_TEST_SMALL_FS=namespace skips
// the first way (to exercise the second).
#pragma once

#include <fcntl.h>
#include <sched.h>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

namespace pathlab::testing {

class SmallFileSystem {
  public:
    SmallFileSystem(const std::filesystem::path& mountPoint, size_t bytes)
        : mountPoint_(mountPoint) {
        std::filesystem::create_directories(mountPoint_);
        const std::string options = "size=" + std::to_string(bytes);
        const char* forced = std::getenv("PATHLAB_TEST_SMALL_FS");
        const bool direct = !forced || std::string(forced) != "namespace";
        if (direct && ::mount("tmpfs", mountPoint_.c_str(), "tmpfs", MS_NOSUID | MS_NODEV,
                              options.c_str()) == 0) {
            mounted_ = true;
            root_ = mountPoint_;
            how_ = "tmpfs mounted with mount(2)";
            return;
        }
        if (direct) why_ = std::string("mount(2) of a tmpfs: ") + std::strerror(errno);
        mountInNamespace(options);
    }
    ~SmallFileSystem() {
        if (mounted_) {
            std::error_code ec;
            for (const auto& entry : std::filesystem::directory_iterator(root_, ec))
                std::filesystem::remove_all(entry.path(), ec);
            ::umount2(mountPoint_.c_str(), MNT_DETACH);
        }
        std::error_code ec;
        std::filesystem::remove(mountPoint_, ec);
    }
    SmallFileSystem(const SmallFileSystem&) = delete;
    SmallFileSystem& operator=(const SmallFileSystem&) = delete;

    bool available() const { return !root_.empty(); }
    const std::string& why() const { return why_; }  // when not available
    const std::string& how() const { return how_; }  // when available
    // Where the test and the programs it starts read and write the file system.
    const std::filesystem::path& root() const { return root_; }

    size_t freeBytes() const {
        struct statvfs s {};
        if (::statvfs(root_.c_str(), &s) != 0) return 0;
        return size_t(s.f_bavail) * s.f_frsize;
    }
    // Fills the file system with root()/filler until `leaveFree` bytes are left.
    void fill(size_t leaveFree) {
        const size_t free = freeBytes();
        const size_t size = free > leaveFree ? free - leaveFree : 0;
        const std::string zeros(64 * 1024, '\0');
        const int fd = ::open((root_ / "filler").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        for (size_t done = 0; fd >= 0 && done < size;) {
            const ssize_t n = ::write(fd, zeros.data(), std::min(zeros.size(), size - done));
            if (n <= 0) break;
            done += size_t(n);
        }
        if (fd >= 0) ::close(fd);
    }
    void removeFiller() { std::filesystem::remove(root_ / "filler"); }

  private:
    // The test process itself moves into a new user and mount namespace
    // (it must be single-threaded then) and stays there: the mount is seen by
    // the test and by every program it starts, under its real path.
    void mountInNamespace(const std::string& options) {
        const uid_t uid = ::geteuid();
        const gid_t gid = ::getegid();
        if (::unshare(CLONE_NEWUSER | CLONE_NEWNS) != 0) {
            why_ += std::string(why_.empty() ? "" : "; ") +
                    "unshare(2) of a user namespace: " + std::strerror(errno);
            return;
        }
        if (!writeIdMaps(uid, gid) ||
            ::mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
            ::mount("tmpfs", mountPoint_.c_str(), "tmpfs", MS_NOSUID | MS_NODEV, options.c_str()) !=
                0) {
            why_ += std::string(why_.empty() ? "" : "; ") +
                    "tmpfs in a user namespace: " + std::strerror(errno);
            return;
        }
        mounted_ = true;
        root_ = mountPoint_;
        how_ = "tmpfs mounted in a user namespace of the test process";
    }
    static bool writeIdMaps(uid_t uid, gid_t gid) {
        auto put = [](const char* file, const std::string& text) {
            const int fd = ::open(file, O_WRONLY);
            if (fd < 0) return false;
            const bool ok = ::write(fd, text.data(), text.size()) == ssize_t(text.size());
            ::close(fd);
            return ok;
        };
        put("/proc/self/setgroups", "deny");
        return put("/proc/self/uid_map", "0 " + std::to_string(uid) + " 1\n") &&
               put("/proc/self/gid_map", "0 " + std::to_string(gid) + " 1\n");
    }

    std::filesystem::path mountPoint_, root_;
    bool mounted_ = false;
    std::string why_, how_;
};

}  // namespace pathlab::testing
