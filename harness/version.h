// `strandbench --version`: what was built (version, commit, build type) and what it runs on
// (the GL and Vulkan devices found, with their Mesa or driver versions).
#pragma once

#include <string>

namespace sb {
// Creates each backend's device briefly to name it; one that is missing is said so.
std::string versionText();
}  // namespace sb
