#pragma once

#include <vulkan/vulkan.h>

#include "backends/device.h"
#include "backends/vulkan/vk_platform.h"

namespace sb {
// Throws DeviceError when the device lacks what desc asks for (logic op, blending on a format).
VkPipeline createGraphicsPipeline(const VulkanPlatform& platform, const PipelineDesc& desc,
                                  VkPipelineLayout layout, VkShaderModule vs, VkShaderModule fs);
}  // namespace sb
