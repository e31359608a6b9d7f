#include "scene/assets.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/paths.h"
#include "scene/pmd_loader.h"

namespace pathlab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kPackage = "0ad-data";
constexpr const char* kZipInDeb = "./usr/share/games/0ad/mods/public/public.zip";
constexpr const char* kPmdInZip = "art/meshes/skeletal/wolf.dae.cached.pmd";
constexpr const char* kDdsInZip = "art/textures/skins/skeletal/animal_wolf_grey.png.cached.dds";
constexpr const char* kNotice =
    "0 A.D. wolf: mesh art/meshes/skeletal/wolf.dae.cached.pmd and texture\n"
    "art/textures/skins/skeletal/animal_wolf_grey.png.cached.dds from Debian's package 0ad-data.\n"
    "Copyright 2010 Wildfire Games. Licence: Creative Commons Attribution-ShareAlike 3.0\n"
    "(CC-BY-SA-3.0), https://creativecommons.org/licenses/by-sa/3.0/.\n";

bool findIn(const fs::path& root, WolfAssets& out) {
    const fs::path dir = root / "wolf";
    std::error_code ec;
    if (!fs::is_regular_file(dir / "wolf.pmd", ec)) return false;
    // The game's DDS first, decoded by us: then the wolf renders the same
    // whether its data came from a shared folder or from the Debian package.
    // (A PNG made from it reads back darkened where its alpha is below one.)
    for (const char* name : {"animal_wolf_grey.dds", "animal_wolf_grey.png"}) {
        if (fs::is_regular_file(dir / name, ec)) {
            out = {dir / "wolf.pmd", dir / name};
            return true;
        }
    }
    return false;
}

std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string lastLine(const fs::path& log) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
        if (!line.empty()) last = line;
    return last;
}

// Runs a shell command with its output in `log`; throws with the log's last
// line when it fails.
void run(const std::string& command, const fs::path& log, const std::string& step) {
    const std::string full = "( " + command + " ) >>" + quote(log.string()) + " 2>&1";
    if (std::system(full.c_str()) != 0) {
        const std::string why = lastLine(log);
        throw InputError("cannot obtain the wolf scene data (" + step + " failed" +
                         (why.empty() ? "" : ": " + why) +
                         "); set PATHLAB_ASSETS to a directory containing wolf/wolf.pmd");
    }
}

void download(const fs::path& assetsDir) {
    std::error_code ec;
    fs::create_directories(assetsDir, ec);
    const fs::path work = assetsDir / (".download-" + std::to_string(getpid()));
    fs::remove_all(work, ec);
    fs::create_directories(work / "x", ec);
    if (ec) throw InputError("cannot create '" + work.string() + "': " + ec.message());
    std::cerr << "pathlab: fetching the wolf scene data from Debian's " << kPackage
              << " package (1.4 GB download, once) into " << (assetsDir / "wolf").string() << "\n";
    const fs::path log = work / "log.txt";
    try {
        const std::string root = getuid() == 0 ? "" : "sudo ";
        run("command -v bsdtar >/dev/null || " + root +
                "env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "
                "--no-install-recommends libarchive-tools",
            log, "installing libarchive-tools");
        run("cd " + quote(work.string()) + " && apt-get download -qq " + kPackage, log,
            "apt-get download");
        run("cd " + quote(work.string()) + " && dpkg-deb --fsys-tarfile " + kPackage +
                "_*_all.deb | bsdtar -xOf - " + kZipInDeb + " | bsdtar -xf - -C x " + kPmdInZip +
                " " + kDdsInZip,
            log, "extraction");
        const fs::path staged = work / "wolf";
        fs::create_directories(staged);
        fs::rename(work / "x" / kPmdInZip, staged / "wolf.pmd");
        fs::rename(work / "x" / kDdsInZip, staged / "animal_wolf_grey.dds");
        readPmd((staged / "wolf.pmd").string());  // fail now, not at every later load
        std::ofstream(staged / "NOTICE.txt") << kNotice;
        // Appears complete under its final name, or not at all. Another
        // process may have got there first; then its copy is as good.
        fs::rename(staged, assetsDir / "wolf", ec);
    } catch (const fs::filesystem_error& e) {
        fs::remove_all(work, ec);
        throw InputError(std::string("cannot obtain the wolf scene data: ") + e.what());
    } catch (...) {
        fs::remove_all(work, ec);
        throw;
    }
    fs::remove_all(work, ec);
}

}  // namespace

bool findWolfAssets(WolfAssets& out) {
    if (const char* env = std::getenv("PATHLAB_ASSETS"); env && *env && findIn(env, out))
        return true;
    return findIn(cacheDirectory() / "assets", out);
}

WolfAssets locateWolfAssets() {
    WolfAssets found;
    if (findWolfAssets(found)) return found;
    download(cacheDirectory() / "assets");
    if (!findWolfAssets(found))
        throw InputError("the wolf scene data is missing after its download");
    return found;
}

}  // namespace pathlab
