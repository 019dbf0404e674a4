// The backends and their platforms, named once for the whole harness: the CLI's
// choices, suites, manifests, `list`, `--version` and the default device.
#pragma once

#include <string>
#include <vector>

namespace sb {

struct BackendNames {
  std::string name;
  std::vector<std::string> platforms;  // the first is the backend's default
};

// gl (egl, osmesa, window) and vulkan (headless, window); the first backend is
// the default. "window" (a GLFW window, needs a display) is last on both: never a default.
inline const std::vector<BackendNames>& backendCatalog() {
  static const std::vector<BackendNames> catalog = {{"gl", {"egl", "osmesa", "window"}},
                                                    {"vulkan", {"headless", "window"}}};
  return catalog;
}

inline std::vector<std::string> backendNames() {
  std::vector<std::string> names;
  for (const auto& b : backendCatalog()) names.push_back(b.name);
  return names;
}

inline bool isWindowPlatform(const std::string& platform) { return platform == "window"; }

inline const std::string& defaultBackend() { return backendCatalog().front().name; }

// The platforms of `backend`; empty for an unknown backend.
inline std::vector<std::string> platformNames(const std::string& backend) {
  for (const auto& b : backendCatalog())
    if (b.name == backend) return b.platforms;
  return {};
}

}  // namespace sb
