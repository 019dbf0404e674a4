#include "backends/vulkan/vk_platform.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "backends/vulkan/vk_util.h"
#include "backends/vulkan/vk_window.h"
#include "backends/window/glfw_window.h"

namespace sb {

namespace {

std::atomic<std::size_t> g_validationMessages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void* /*user*/) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    g_validationMessages.fetch_add(1);
    std::fprintf(stderr, "[vulkan validation %s] %s\n",
                 severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning",
                 data != nullptr && data->pMessage != nullptr ? data->pMessage : "");
  }
  return VK_FALSE;
}

std::string versionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
  return std::any_of(exts.begin(), exts.end(),
                     [&](const auto& x) { return std::strcmp(x.extensionName, name) == 0; });
}

}  // namespace

std::size_t validationMessageCount() { return g_validationMessages.load(); }

VulkanPlatform::VulkanPlatform(bool validation, const VulkanWindowRequest* request) {
  try {
    std::vector<const char*> windowExtensions;
    if (request) {
      window = std::make_unique<GlfwWindow>(GlfwWindow::Api::None, request->width, request->height,
                                            request->title);
      windowExtensions = windowInstanceExtensions();
    }
    createInstance(validation || envFlag("SB_VALIDATION"), windowExtensions);
    if (window) surface = createWindowSurface(instance, *window);
    pickPhysicalDevice();
    createLogicalDevice();
  } catch (...) {
    destroy();
    throw;
  }
}

VulkanPlatform::~VulkanPlatform() { destroy(); }

void VulkanPlatform::createInstance(bool validation,
                                    const std::vector<const char*>& windowExtensions) {
  uint32_t loaderVersion = VK_API_VERSION_1_0;
  if (vkEnumerateInstanceVersion(&loaderVersion) != VK_SUCCESS ||
      loaderVersion < VK_API_VERSION_1_3) {
    throw DeviceError("no Vulkan device found: the Vulkan loader supports only version " +
                      versionString(loaderVersion) + "; 1.3 is required");
  }
  std::vector<const char*> layers;
  std::vector<const char*> extensions = windowExtensions;
  bool debugUtils = false;
  if (validation) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> props(n);
    vkEnumerateInstanceLayerProperties(&n, props.data());
    const bool haveLayer = std::any_of(props.begin(), props.end(), [](const auto& p) {
      return std::strcmp(p.layerName, "VK_LAYER_KHRONOS_validation") == 0;
    });
    if (haveLayer) {
      layers.push_back("VK_LAYER_KHRONOS_validation");
    } else {
      std::fprintf(stderr,
                   "strandbench: warning: VK_LAYER_KHRONOS_validation is not installed; "
                   "running without Vulkan validation\n");
    }
    uint32_t e = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &e, nullptr);
    std::vector<VkExtensionProperties> exts(e);
    vkEnumerateInstanceExtensionProperties(nullptr, &e, exts.data());
    debugUtils = std::any_of(exts.begin(), exts.end(), [](const auto& x) {
      return std::strcmp(x.extensionName, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) == 0;
    });
    if (debugUtils) {
      extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    } else {
      std::fprintf(stderr,
                   "strandbench: warning: VK_EXT_debug_utils is missing; validation messages "
                   "are not counted\n");
    }
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "strandbench";
  app.pEngineName = "strandbench";
  app.apiVersion = VK_API_VERSION_1_3;
  VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  dbg.pfnUserCallback = debugCallback;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pNext = debugUtils ? &dbg : nullptr;  // also covers create/destroy instance
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = static_cast<uint32_t>(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  VkResult r = vkCreateInstance(&ci, nullptr, &instance);
  if (r != VK_SUCCESS) {
    instance = VK_NULL_HANDLE;
    throw DeviceError(std::string("no Vulkan device found: vkCreateInstance failed with ") +
                      resultName(r) +
                      " (is a Vulkan driver such as mesa-vulkan-drivers "
                      "installed?)");
  }
  if (debugUtils) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create != nullptr) {
      check(create(instance, &dbg, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
    }
  }
}

void VulkanPlatform::pickPhysicalDevice() {
  uint32_t n = 0;
  VkResult r = vkEnumeratePhysicalDevices(instance, &n, nullptr);
  if (r != VK_SUCCESS || n == 0) {
    throw DeviceError(
        "no Vulkan device found: no physical device (install a Vulkan driver, e.g. "
        "mesa-vulkan-drivers for lavapipe)");
  }
  std::vector<VkPhysicalDevice> devs(n);
  check(vkEnumeratePhysicalDevices(instance, &n, devs.data()), "vkEnumeratePhysicalDevices");
  devs.resize(n);

  struct Candidate {
    VkPhysicalDevice pd;
    VkPhysicalDeviceProperties props;
    uint32_t family;
  };
  std::vector<Candidate> usable;
  std::string seen;
  for (VkPhysicalDevice pd : devs) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    seen += std::string(seen.empty() ? "" : ", ") + props.deviceName + " (Vulkan " +
            versionString(props.apiVersion) + ")";
    if (props.apiVersion < VK_API_VERSION_1_3) continue;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13};
    vkGetPhysicalDeviceFeatures2(pd, &f2);
    if (!f13.dynamicRendering) continue;
    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> qs(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, qs.data());
    const VkQueueFlags want = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if (surface != VK_NULL_HANDLE && !hasDeviceExtension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
      continue;
    for (uint32_t i = 0; i < qn; ++i) {
      VkBool32 presents = VK_TRUE;
      if (surface != VK_NULL_HANDLE)
        vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &presents);
      if ((qs[i].queueFlags & want) == want && presents) {
        usable.push_back({pd, props, i});
        break;
      }
    }
  }
  const Candidate* pick = nullptr;
  if (const char* want = std::getenv("SB_VULKAN_DEVICE"); want != nullptr && *want != '\0') {
    for (const Candidate& c : usable) {
      if (std::strstr(c.props.deviceName, want) != nullptr) {
        pick = &c;
        break;
      }
    }
    if (pick == nullptr) {
      throw DeviceError(std::string("no Vulkan device found matching SB_VULKAN_DEVICE='") + want +
                        "' (devices: " + seen + ")");
    }
  } else {
    auto rank = [](VkPhysicalDeviceType t) {
      switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
          return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
          return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
          return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
          return 3;
        default:
          return 4;
      }
    };
    for (const Candidate& c : usable) {
      if (pick == nullptr || rank(c.props.deviceType) < rank(pick->props.deviceType)) pick = &c;
    }
    if (pick == nullptr) {
      throw DeviceError(
          std::string("no Vulkan device found with Vulkan 1.3, dynamic rendering and a "
                      "graphics+compute queue") +
          (surface != VK_NULL_HANDLE ? " that presents to the window" : "") + " (devices: " + seen +
          ")");
    }
  }
  physical = pick->pd;
  queueFamily = pick->family;
  limits = pick->props.limits;
  timestampPeriod = pick->props.limits.timestampPeriod;

  uint32_t qn = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &qn, nullptr);
  std::vector<VkQueueFamilyProperties> qs(qn);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &qn, qs.data());
  timestampBits = qs[queueFamily].timestampValidBits;
  // lavapipe writes a pass's end timestamp before llvmpipe has finished
  // rasterizing it (measured: 0.6 ms by timestamps vs 33 ms by wall clock for
  // a 30k-segment pass), so CPU devices are timed per pass on the CPU, as GL is.
  cpuDevice = pick->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  info.cpuDevice = cpuDevice;
  cpuTiming =
      timestampBits == 0 || envFlag("SB_VULKAN_CPU_TIMING") ||
      (pick->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU && !envFlag("SB_VULKAN_GPU_TIMING"));

  VkPhysicalDeviceDriverProperties drv{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &drv};
  vkGetPhysicalDeviceProperties2(physical, &p2);
  uniformsAsStorage =
      drv.driverID == VK_DRIVER_ID_MESA_LLVMPIPE && !envFlag("SB_VULKAN_UNIFORM_BUFFERS");
  info.backend = "vulkan";
  info.timing = cpuTiming ? "cpu clock per pass (submit and wait)" : "gpu timestamps";
  info.platform = surface != VK_NULL_HANDLE ? "window" : "headless";
  info.maxColorAttachments = pick->props.limits.maxColorAttachments;
  info.maxStorageBufferBytes = pick->props.limits.maxStorageBufferRange;
  info.fragmentShaderInterlock =
      hasDeviceExtension(physical, VK_EXT_FRAGMENT_SHADER_INTERLOCK_EXTENSION_NAME);
  // Multisampled render targets: counts both colour and depth attachments take.
  info.sampleCounts = (pick->props.limits.framebufferColorSampleCounts &
                       pick->props.limits.framebufferDepthSampleCounts) |
                      1u;
  info.device = pick->props.deviceName;
  info.apiVersion = versionString(pick->props.apiVersion);
  info.timestamps = timestampBits != 0;
  // Ray queries: confirmed by their features in createLogicalDevice.
  info.rayQuery = hasDeviceExtension(physical, VK_KHR_RAY_QUERY_EXTENSION_NAME) &&
                  hasDeviceExtension(physical, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) &&
                  hasDeviceExtension(physical, VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
  info.meshShaders = hasDeviceExtension(physical, VK_EXT_MESH_SHADER_EXTENSION_NAME);
  if (drv.driverName[0] != '\0') {
    info.driver = std::string(drv.driverName) + " " + drv.driverInfo;
  } else {
    info.driver = "driver version " + std::to_string(pick->props.driverVersion) + ", Vulkan " +
                  versionString(pick->props.apiVersion);
  }
}

void VulkanPlatform::createLogicalDevice() {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, exts.data());
  const bool haveLineExt = std::any_of(exts.begin(), exts.end(), [](const auto& x) {
    return std::strcmp(x.extensionName, VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME) == 0;
  });
  memoryBudget = std::any_of(exts.begin(), exts.end(), [](const auto& x) {
    return std::strcmp(x.extensionName, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME) == 0;
  });

  // Enable every supported core feature (the techniques' shaders may use image
  // or int64 atomics, logic op, independent blend...), except robustness, which
  // only costs speed, and sparse/protected features, which need more setup.
  // Ray queries (the rt technique's hardware tier): their two features,
  // chained only where the extensions are offered.
  VkPhysicalDeviceRayQueryFeaturesKHR rayQueryFeature{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR accelFeature{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, &rayQueryFeature};
  // Mesh shaders (the mesh geometry path): the meshShader feature alone, no task shaders.
  VkPhysicalDeviceMeshShaderFeaturesEXT meshFeature{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_FEATURES_EXT};
  VkPhysicalDeviceLineRasterizationFeaturesEXT line{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT,
      info.rayQuery ? &accelFeature : nullptr};
  if (info.meshShaders) {
    meshFeature.pNext = line.pNext;
    line.pNext = &meshFeature;
  }
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                       haveLineExt ? static_cast<void*>(&line) : line.pNext};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f12};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11};
  vkGetPhysicalDeviceFeatures2(physical, &f2);
  f2.features.robustBufferAccess = VK_FALSE;
  f2.features.sparseBinding = VK_FALSE;
  f2.features.sparseResidencyBuffer = VK_FALSE;
  f2.features.sparseResidencyImage2D = VK_FALSE;
  f2.features.sparseResidencyImage3D = VK_FALSE;
  f2.features.sparseResidency2Samples = VK_FALSE;
  f2.features.sparseResidency4Samples = VK_FALSE;
  f2.features.sparseResidency8Samples = VK_FALSE;
  f2.features.sparseResidency16Samples = VK_FALSE;
  f2.features.sparseResidencyAliased = VK_FALSE;
  f11.protectedMemory = VK_FALSE;
  f13.robustImageAccess = VK_FALSE;
  info.rayQuery = info.rayQuery && accelFeature.accelerationStructure == VK_TRUE &&
                  rayQueryFeature.rayQuery == VK_TRUE && f12.bufferDeviceAddress == VK_TRUE;
  // Only what the lookup needs: no capture/replay, indirect or host builds.
  accelFeature = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR,
                  &rayQueryFeature};
  accelFeature.accelerationStructure = VK_TRUE;
  // Only the mesh stage itself: no task shaders, multiview or shading rate.
  info.meshShaders = info.meshShaders && meshFeature.meshShader == VK_TRUE;
  meshFeature = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_FEATURES_EXT};
  meshFeature.meshShader = VK_TRUE;
  rayQueryFeature.pNext = nullptr;
  line.pNext = info.rayQuery ? &accelFeature : nullptr;
  if (info.meshShaders) {
    meshFeature.pNext = line.pNext;
    line.pNext = &meshFeature;
  }
  f12.bufferDeviceAddressCaptureReplay = VK_FALSE;
  f12.bufferDeviceAddressMultiDevice = VK_FALSE;
  logicOp = f2.features.logicOp == VK_TRUE;
  statistics = f2.features.pipelineStatisticsQuery == VK_TRUE && f12.hostQueryReset == VK_TRUE;
  preciseOcclusion = f2.features.occlusionQueryPrecise == VK_TRUE;
  info.counters = statistics ? std::string("pipeline statistics queries, ") +
                                   (preciseOcclusion ? "precise " : "") + "occlusion queries"
                             : "";
  // SB_VULKAN_LINES=default keeps the API's default (rectangular) lines, to
  // measure how far they are from GL's aliased lines.
  const char* linesEnv = std::getenv("SB_VULKAN_LINES");
  const bool wantBresenham = !(linesEnv && std::string(linesEnv) == "default");
  bresenham = wantBresenham && haveLineExt && line.bresenhamLines == VK_TRUE;
  info.lines = bresenham ? "bresenham (VK_EXT_line_rasterization)" : "default (rectangular)";
  line.rectangularLines = VK_FALSE;
  line.smoothLines = VK_FALSE;
  line.stippledRectangularLines = VK_FALSE;
  line.stippledBresenhamLines = VK_FALSE;
  line.stippledSmoothLines = VK_FALSE;
  line.bresenhamLines = bresenham ? VK_TRUE : VK_FALSE;

  std::vector<const char*> enabled;
  if (bresenham) enabled.push_back(VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME);
  if (surface != VK_NULL_HANDLE) enabled.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  if (info.rayQuery)
    for (const char* e :
         {VK_KHR_RAY_QUERY_EXTENSION_NAME, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
          VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME})
      enabled.push_back(e);
  if (info.meshShaders) enabled.push_back(VK_EXT_MESH_SHADER_EXTENSION_NAME);
  // Unchained where unused: a feature struct of an extension not enabled is invalid.
  if (!bresenham) f13.pNext = line.pNext;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qi.queueFamilyIndex = queueFamily;
  qi.queueCount = 1;
  qi.pQueuePriorities = &priority;
  VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &f2};
  ci.queueCreateInfoCount = 1;
  ci.pQueueCreateInfos = &qi;
  ci.enabledExtensionCount = static_cast<uint32_t>(enabled.size());
  ci.ppEnabledExtensionNames = enabled.data();
  check(vkCreateDevice(physical, &ci, nullptr, &device), "vkCreateDevice");
  vkGetDeviceQueue(device, queueFamily, 0, &queue);
  if (info.meshShaders) {
    drawMeshTasks = reinterpret_cast<PFN_vkCmdDrawMeshTasksEXT>(
        vkGetDeviceProcAddr(device, "vkCmdDrawMeshTasksEXT"));
    VkPhysicalDeviceMeshShaderPropertiesEXT mp{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_PROPERTIES_EXT};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &mp};
    vkGetPhysicalDeviceProperties2(physical, &p2);
    maxMeshGroupsX = mp.maxMeshWorkGroupCount[0];
    maxMeshGroupsTotal = mp.maxMeshWorkGroupTotalCount;
    info.meshShaders = drawMeshTasks != nullptr;
  }
  vkGetPhysicalDeviceMemoryProperties(physical, &memProps);
}
void VulkanPlatform::destroy() {
  if (device != VK_NULL_HANDLE) {
    vkDestroyDevice(device, nullptr);
    device = VK_NULL_HANDLE;
  }
  if (messenger != VK_NULL_HANDLE) {
    auto destroyFn = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroyFn != nullptr) destroyFn(instance, messenger, nullptr);
    messenger = VK_NULL_HANDLE;
  }
  if (surface != VK_NULL_HANDLE) {
    vkDestroySurfaceKHR(instance, surface, nullptr);
    surface = VK_NULL_HANDLE;
  }
  if (instance != VK_NULL_HANDLE) {
    vkDestroyInstance(instance, nullptr);
    instance = VK_NULL_HANDLE;
  }
}

}  // namespace sb
