// The Vulkan implementation of Device: headless instance, Vulkan 1.3, dynamic
// rendering, one graphics+compute queue, GLSL compiled at runtime by glslang.
#pragma once

#include <memory>

#include "backends/device.h"

namespace sb {

// Throws DeviceError ("no Vulkan device found ...") when no usable device exists.
// Device choice: env SB_VULKAN_DEVICE (substring of deviceName), else discrete,
// integrated, then CPU. Validation: opts.validation or env SB_VALIDATION=1.
std::unique_ptr<Device> createVulkanDevice(const DeviceOptions& opts);

}  // namespace sb
