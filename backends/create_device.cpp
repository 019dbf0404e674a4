#include "backends/gl/gl_driver.h"
#include "backends/vulkan/vk_driver.h"

namespace sb {

std::unique_ptr<Device> createDevice(const DeviceOptions& opts) {
  if (opts.backend == "gl") return std::make_unique<Device>(createGLDriver(opts));
  if (opts.backend == "vulkan") return std::make_unique<Device>(createVulkanDriver(opts));
  throw DeviceError("unknown backend '" + opts.backend + "' (valid: gl, vulkan)");
}

}  // namespace sb
