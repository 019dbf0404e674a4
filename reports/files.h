// Small file helpers shared by the commands that write results.
#pragma once

#include <filesystem>
#include <string>

namespace sb {

// Writes `contents` to a temporary file beside `path` and renames it into place,
// so a reader sees the old file or the whole new one, never half of it.
// Throws InputError naming the path when the folder is missing or not writable.
void writeFileAtomic(const std::filesystem::path& path, const std::string& contents);

// The whole file; throws InputError naming the path when it cannot be read.
std::string readTextFile(const std::filesystem::path& path);

}  // namespace sb
