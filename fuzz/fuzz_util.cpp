#include "fuzz_util.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace pathlab::fuzz {
namespace fs = std::filesystem;

namespace {

struct ScratchDir {
    fs::path path;
    ScratchDir() {
        std::string pattern = (fs::temp_directory_path() / "pathlab-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) {
            std::perror("pathlab fuzz: cannot create a scratch directory");
            std::abort();
        }
        path = pattern;
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

}  // namespace

const fs::path& scratchDir() {
    static const ScratchDir dir;
    return dir.path;
}

std::string writeScratchFile(const std::string& name, std::string_view bytes) {
    const fs::path path = scratchDir() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) {
        std::fprintf(stderr, "pathlab fuzz: cannot write '%s'\n", path.c_str());
        std::abort();
    }
    return path.string();
}

}  // namespace pathlab::fuzz
