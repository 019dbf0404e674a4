// Where a Vulkan device comes from, beside the GL platforms (backends/gl/gl_platform.h):
// the instance (with validation layers when asked), the choice of physical
// device and the logical device with the features the techniques use.
#pragma once

#include <vulkan/vulkan.h>

#include <memory>
#include <string>

#include "backends/device.h"

namespace sb {

class GlfwWindow;

// The window platform's window (`--platform window`): its first size and title.
struct VulkanWindowRequest {
  uint32_t width = 512, height = 512;
  std::string title = "strandbench";
};

class VulkanPlatform {
 public:
  // Throws DeviceError ("no Vulkan device found ...") when no usable device exists.
  // Device choice: env SB_VULKAN_DEVICE (substring of deviceName), else discrete,
  // integrated, then CPU. Validation: `validation` or env SB_VALIDATION=1.
  // With a window request: a GLFW window and its surface, the instance
  // extensions GLFW needs, a queue family that can present to the surface and
  // VK_KHR_swapchain (DeviceError "no display: ..." without a display).
  explicit VulkanPlatform(bool validation, const VulkanWindowRequest* window = nullptr);
  ~VulkanPlatform();
  VulkanPlatform(const VulkanPlatform&) = delete;
  VulkanPlatform& operator=(const VulkanPlatform&) = delete;

  std::unique_ptr<GlfwWindow> window;  // destroyed after the surface and instance
  VkInstance instance = VK_NULL_HANDLE;
  VkSurfaceKHR surface = VK_NULL_HANDLE;  // window platform
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  VkPhysicalDeviceLimits limits{};
  VkPhysicalDeviceMemoryProperties memProps{};
  float timestampPeriod = 1.0f;
  uint32_t timestampBits = 0;
  bool cpuTiming = false;     // time passes on the CPU (CPU devices, or asked for)
  bool logicOp = false;       // the logicOp feature
  bool bresenham = false;     // Bresenham lines (VK_EXT_line_rasterization)
  bool memoryBudget = false;  // VK_EXT_memory_budget (queried, not enabled: no device state)
  bool cpuDevice = false;     // VK_PHYSICAL_DEVICE_TYPE_CPU: its memory is the host's
  // Uniform blocks are read through storage buffers (same std140 layout): on
  // lavapipe (Mesa 22.3), a shader that reads a uniform buffer in a loop bound
  // or branch is recompiled with the values inlined whenever its pipeline or
  // uniform buffers are bound (every draw here), and the compiled variants are
  // never freed (lvp_execute.c, update_inline_shader_state): 1-8 MiB a frame,
  // for the process's life. Storage buffers are not inlined.
  // SB_VULKAN_UNIFORM_BUFFERS=1 keeps uniform buffers (to measure the
  // difference).
  bool uniformsAsStorage = false;
  // Work counters: pipeline statistics queries, reset from the host
  // (pipelineStatisticsQuery and hostQueryReset), precise occlusion queries.
  bool statistics = false;
  bool preciseOcclusion = false;
  // Mesh pipelines (info.meshShaders: VK_EXT_mesh_shader and its meshShader feature,
  // enabled only then): the draw and the most workgroups one draw may have (x, total).
  PFN_vkCmdDrawMeshTasksEXT drawMeshTasks = nullptr;
  uint32_t maxMeshGroupsX = 0, maxMeshGroupsTotal = 0;
  DeviceInfo info;  // backend, platform, device, driver, timing, lines

 private:
  void createInstance(bool validation, const std::vector<const char*>& windowExtensions);
  void pickPhysicalDevice();
  void createLogicalDevice();
  void destroy();
};

}  // namespace sb
