#include "harness/version.h"

#include <sstream>

#include "backends/device.h"
#include "sb_version.h"

namespace sb {

std::string versionText() {
  std::ostringstream out;
  out << "strandbench " << SB_VERSION << "\n";
  out << "commit: " << SB_GIT_COMMIT << (SB_GIT_DIRTY ? " (with uncommitted changes)" : "") << "\n";
  out << "build type: " << SB_BUILD_TYPE << "\n";
  const struct {
    const char* label;
    DeviceOptions opts;
  } devices[] = {{"gl (egl)", {"gl", "egl", false}},
                 {"gl (osmesa)", {"gl", "osmesa", false}},
                 {"vulkan", {"vulkan", "headless", false}}};
  for (const auto& d : devices) {
    out << d.label << ": ";
    try {
      const DeviceInfo info = createDevice(d.opts)->info();
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
