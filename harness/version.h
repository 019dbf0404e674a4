// `strandbench --version`: what was built (version, commit, build type) and what it runs on:
// every driver found (system and each folder under drivers/), with the GL and Vulkan
// devices of each, their versions and the capabilities strandbench uses.
#pragma once

#include <string>

namespace sb {
// Probes each driver in a child process of its own (versionProbeText there).
std::string versionText();
// This process's devices, one per backend and platform (creates each briefly; one
// that is missing is said so): what `strandbench --version-probe` prints.
std::string versionProbeText();
}  // namespace sb
