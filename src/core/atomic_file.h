// Writing files so that a reader, a crash or a full disk never sees half of
// one: the bytes go to a temporary beside the target, are flushed to disk and
// renamed into place. Failures name the target and the reason in one line.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace pathlab {

// Writes `bytes` to `path` atomically. Throws InputError naming `path` and the
// problem (e.g. "no space left on device writing 'out.exr'"); the temporary is
// removed and an existing file at `path` is left as it was.
void writeFileAtomic(const std::string& path, std::string_view bytes);

// The one-line description of a failed write of `path` with errno `error`.
std::string writeErrorMessage(const std::string& path, int error);

// The temporary a write of `path` by this process uses: ".NAME.tmp.PID"
// beside it.
std::string temporaryPathFor(const std::string& path);

// Removes, under `dir` (recursively), the temporaries that processes which no
// longer run left behind (a write interrupted by kill -9 or a power cut).
// Returns how many were removed.
int removeStaleTemporaries(const std::filesystem::path& dir);

// Whether `name` (a file name, no directory) is such a temporary.
bool isTemporaryName(const std::string& name);

}  // namespace pathlab
