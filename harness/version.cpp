#include "harness/version.h"

#include <sstream>

#include "backends/device.h"
#include "harness/backend_names.h"
#include "sb_version.h"

namespace sb {

std::string versionText() {
  std::ostringstream out;
  out << "strandbench " << SB_VERSION << "\n";
  out << "commit: " << SB_GIT_COMMIT << (SB_GIT_DIRTY ? " (with uncommitted changes)" : "") << "\n";
  out << "build type: " << SB_BUILD_TYPE << "\n";
  // Every platform of every backend; the platform is named where a backend has several.
  for (const auto& b : backendCatalog())
    for (const auto& platform : b.platforms) {
      out << b.name << (b.platforms.size() > 1 ? " (" + platform + ")" : "") << ": ";
      if (isWindowPlatform(platform)) {  // not opened here: a window would flash up
        out << "a GLFW window (needs a display; not opened by --version)\n";
        continue;
      }
      try {
        const DeviceInfo info = createDevice({b.name, platform, false})->info();
        out << info.device << "; " << info.driver << "\n";
      } catch (const std::exception& e) {
        out << "unavailable (" << e.what() << ")\n";
      }
    }
  std::string text = out.str();
  text.pop_back();  // CLI11 ends the message with its own newline
  return text;
}

}  // namespace sb
