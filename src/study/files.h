// Small file and provenance helpers of the study runner.
#pragma once

#include <filesystem>
#include <string>

namespace pathlab {

// Writes `content` under a temporary name beside `path`, flushes it to disk
// and renames it into place: readers see the old file or the whole new one
// (writeFileAtomic; throws InputError naming the file and the cause).
void writeTextFileAtomic(const std::filesystem::path& path, const std::string& content);

// The commit of the source tree pathlab was built from (`git rev-parse HEAD`
// in PATHLAB_SOURCE_DIR, read once at run time), with "-dirty" appended when
// tracked files differ from that commit, or "unknown" when that is not a git
// checkout or git is missing.
const std::string& sourceGitCommit();

// The current UTC time as ISO 8601, e.g. "2026-11-22T01:23:45Z".
std::string isoTimestampUtc();

}  // namespace pathlab
