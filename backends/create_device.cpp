#include "backends/gl/gl_device.h"
#include "backends/vulkan/vk_device.h"

namespace sb {

std::unique_ptr<Device> createDevice(const DeviceOptions& opts) {
  if (opts.backend == "gl") return createGLDevice(opts);
  if (opts.backend == "vulkan") return createVulkanDevice(opts);
  throw DeviceError("unknown backend '" + opts.backend + "' (valid: gl, vulkan)");
}

}  // namespace sb
