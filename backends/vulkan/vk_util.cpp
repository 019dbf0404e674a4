#include "backends/vulkan/vk_util.h"

#include <cstdlib>
#include <cstring>
#include <iterator>
#include <string>
#include <utility>

#include "backends/driver.h"

namespace sb {

const char* resultName(VkResult r) {
#define SB_VK_RESULT(x) \
  { x, #x }
  static constexpr std::pair<VkResult, const char*> kNames[] = {
      SB_VK_RESULT(VK_SUCCESS),
      SB_VK_RESULT(VK_NOT_READY),
      SB_VK_RESULT(VK_TIMEOUT),
      SB_VK_RESULT(VK_INCOMPLETE),
      SB_VK_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY),
      SB_VK_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY),
      SB_VK_RESULT(VK_ERROR_INITIALIZATION_FAILED),
      SB_VK_RESULT(VK_ERROR_DEVICE_LOST),
      SB_VK_RESULT(VK_ERROR_MEMORY_MAP_FAILED),
      SB_VK_RESULT(VK_ERROR_LAYER_NOT_PRESENT),
      SB_VK_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT),
      SB_VK_RESULT(VK_ERROR_FEATURE_NOT_PRESENT),
      SB_VK_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER),
      SB_VK_RESULT(VK_ERROR_TOO_MANY_OBJECTS),
      SB_VK_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED),
      SB_VK_RESULT(VK_ERROR_FRAGMENTED_POOL),
      SB_VK_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY),
  };
#undef SB_VK_RESULT
  for (const auto& [value, name] : kNames)
    if (value == r) return name;
  return "VkResult error";
}

void check(VkResult r, const char* what) {
  if (r == VK_ERROR_OUT_OF_HOST_MEMORY || r == VK_ERROR_OUT_OF_DEVICE_MEMORY)
    throw OutOfMemoryError(std::string("vulkan: ") + what + " failed: " + resultName(r));
  if (r != VK_SUCCESS) {
    throw DeviceError(std::string("vulkan: ") + what + " failed: " + resultName(r) + " (" +
                      std::to_string(static_cast<int>(r)) + ")");
  }
}

bool envFlag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' && std::strcmp(v, "0") != 0;
}

// Tables in the order of the enums in backends/device.h.
constexpr VkFormat kFormats[] = {VK_FORMAT_R8G8B8A8_UNORM,      VK_FORMAT_R16G16B16A16_SFLOAT,
                                 VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32_SFLOAT,
                                 VK_FORMAT_R32G32_SFLOAT,       VK_FORMAT_R32_UINT,
                                 VK_FORMAT_R32G32B32A32_UINT,   VK_FORMAT_D32_SFLOAT};
static_assert(std::size(kFormats) == std::size_t(Format::Depth32F) + 1);
constexpr VkCompareOp kCompare[] = {VK_COMPARE_OP_NEVER,         VK_COMPARE_OP_LESS,
                                    VK_COMPARE_OP_LESS_OR_EQUAL, VK_COMPARE_OP_EQUAL,
                                    VK_COMPARE_OP_GREATER,       VK_COMPARE_OP_GREATER_OR_EQUAL,
                                    VK_COMPARE_OP_NOT_EQUAL,     VK_COMPARE_OP_ALWAYS};
static_assert(std::size(kCompare) == std::size_t(CompareOp::Always) + 1);
constexpr VkBlendFactor kBlendFactors[] = {
    VK_BLEND_FACTOR_ZERO,      VK_BLEND_FACTOR_ONE,
    VK_BLEND_FACTOR_SRC_COLOR, VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR,
    VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
    VK_BLEND_FACTOR_DST_COLOR, VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR,
    VK_BLEND_FACTOR_DST_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA};
static_assert(std::size(kBlendFactors) == std::size_t(BlendFactor::OneMinusDstAlpha) + 1);
constexpr VkBlendOp kBlendOps[] = {VK_BLEND_OP_ADD, VK_BLEND_OP_SUBTRACT,
                                   VK_BLEND_OP_REVERSE_SUBTRACT, VK_BLEND_OP_MIN, VK_BLEND_OP_MAX};
static_assert(std::size(kBlendOps) == std::size_t(BlendOp::Max) + 1);
constexpr VkDescriptorType kDescriptors[] = {
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
    VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR};
static_assert(std::size(kDescriptors) == std::size_t(BindingKind::AccelerationStructure) + 1);

VkFormat toVkFormat(Format f) { return byEnum(kFormats, f); }
VkCompareOp toVk(CompareOp op) { return byEnum(kCompare, op); }
VkBlendFactor toVk(BlendFactor f) { return byEnum(kBlendFactors, f); }
VkBlendOp toVk(BlendOp op) { return byEnum(kBlendOps, op); }
VkDescriptorType toVk(BindingKind k) { return byEnum(kDescriptors, k); }

}  // namespace sb
