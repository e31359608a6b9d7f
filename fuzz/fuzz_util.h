// Helpers shared by the fuzz targets: a scratch directory for loaders that
// read files by path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace pathlab::fuzz {

// A directory of this process's own under the system's temporary directory,
// created on first use and removed when the process exits normally.
const std::filesystem::path& scratchDir();

// Writes `bytes` to scratchDir()/name (replacing it) and returns the path.
std::string writeScratchFile(const std::string& name, std::string_view bytes);

// The fuzzer's input as text.
inline std::string_view asText(const uint8_t* data, size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

}  // namespace pathlab::fuzz
