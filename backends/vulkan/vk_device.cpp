// Vulkan Device: see vk_device.h and backends/device.h for the contract.
//
// Design (simple and correct over clever):
//  - One command buffer per frame, recorded between beginFrame() and endFrame();
//    endFrame() submits and waits on a fence. Work outside a frame (uploads,
//    readback, texture initialisation) goes through a one-shot command buffer
//    that is submitted and waited for at once.
//  - Every pass and dispatch starts with a full memory barrier (all commands ->
//    all commands, memory write -> memory read|write) plus the image layout
//    transitions it needs, so storage-buffer writes of one pass are visible to
//    the next. Each image's current layout is tracked on the CPU in record order.
//  - Per-draw descriptor sets come from pools that are reset after each frame.
//  - Timing: one timestamp pair per pass on GPUs; on CPU devices (lavapipe),
//    without timestamps, or with SB_VULKAN_CPU_TIMING=1, each pass is submitted
//    alone and timed on the CPU (SB_VULKAN_GPU_TIMING=1 forces timestamps).
#include "backends/vulkan/vk_device.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "backends/shader_source.h"
#include "backends/vulkan/vk_shader.h"

namespace sb {

namespace {

std::atomic<std::size_t> g_validationMessages{0};

constexpr uint32_t kQueriesPerPool = 128;  // even: a pass's pair never straddles pools
constexpr VkDeviceSize kMaxCmdUpdateBytes = 65536;

const char* resultName(VkResult r) {
  switch (r) {
    case VK_SUCCESS:
      return "VK_SUCCESS";
    case VK_NOT_READY:
      return "VK_NOT_READY";
    case VK_TIMEOUT:
      return "VK_TIMEOUT";
    case VK_INCOMPLETE:
      return "VK_INCOMPLETE";
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
      return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED:
      return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST:
      return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED:
      return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT:
      return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT:
      return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT:
      return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS:
      return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_FORMAT_NOT_SUPPORTED:
      return "VK_ERROR_FORMAT_NOT_SUPPORTED";
    case VK_ERROR_FRAGMENTED_POOL:
      return "VK_ERROR_FRAGMENTED_POOL";
    case VK_ERROR_OUT_OF_POOL_MEMORY:
      return "VK_ERROR_OUT_OF_POOL_MEMORY";
    default:
      return "VkResult error";
  }
}

void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) {
    throw DeviceError(std::string("vulkan: ") + what + " failed: " + resultName(r) + " (" +
                      std::to_string(static_cast<int>(r)) + ")");
  }
}

bool envFlag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' && std::strcmp(v, "0") != 0;
}

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

VkFormat toVkFormat(Format f) {
  switch (f) {
    case Format::RGBA8:
      return VK_FORMAT_R8G8B8A8_UNORM;
    case Format::RGBA16F:
      return VK_FORMAT_R16G16B16A16_SFLOAT;
    case Format::RGBA32F:
      return VK_FORMAT_R32G32B32A32_SFLOAT;
    case Format::R32F:
      return VK_FORMAT_R32_SFLOAT;
    case Format::RG32F:
      return VK_FORMAT_R32G32_SFLOAT;
    case Format::R32UI:
      return VK_FORMAT_R32_UINT;
    case Format::RGBA32UI:
      return VK_FORMAT_R32G32B32A32_UINT;
    case Format::Depth32F:
      return VK_FORMAT_D32_SFLOAT;
  }
  return VK_FORMAT_UNDEFINED;
}

VkCompareOp toVk(CompareOp op) {
  switch (op) {
    case CompareOp::Never:
      return VK_COMPARE_OP_NEVER;
    case CompareOp::Less:
      return VK_COMPARE_OP_LESS;
    case CompareOp::LessEqual:
      return VK_COMPARE_OP_LESS_OR_EQUAL;
    case CompareOp::Equal:
      return VK_COMPARE_OP_EQUAL;
    case CompareOp::Greater:
      return VK_COMPARE_OP_GREATER;
    case CompareOp::GreaterEqual:
      return VK_COMPARE_OP_GREATER_OR_EQUAL;
    case CompareOp::NotEqual:
      return VK_COMPARE_OP_NOT_EQUAL;
    case CompareOp::Always:
      return VK_COMPARE_OP_ALWAYS;
  }
  return VK_COMPARE_OP_ALWAYS;
}

VkBlendFactor toVk(BlendFactor f) {
  switch (f) {
    case BlendFactor::Zero:
      return VK_BLEND_FACTOR_ZERO;
    case BlendFactor::One:
      return VK_BLEND_FACTOR_ONE;
    case BlendFactor::SrcColor:
      return VK_BLEND_FACTOR_SRC_COLOR;
    case BlendFactor::OneMinusSrcColor:
      return VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR;
    case BlendFactor::SrcAlpha:
      return VK_BLEND_FACTOR_SRC_ALPHA;
    case BlendFactor::OneMinusSrcAlpha:
      return VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::DstColor:
      return VK_BLEND_FACTOR_DST_COLOR;
    case BlendFactor::OneMinusDstColor:
      return VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR;
    case BlendFactor::DstAlpha:
      return VK_BLEND_FACTOR_DST_ALPHA;
    case BlendFactor::OneMinusDstAlpha:
      return VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
  }
  return VK_BLEND_FACTOR_ONE;
}

VkBlendOp toVk(BlendOp op) {
  switch (op) {
    case BlendOp::Add:
      return VK_BLEND_OP_ADD;
    case BlendOp::Subtract:
      return VK_BLEND_OP_SUBTRACT;
    case BlendOp::ReverseSubtract:
      return VK_BLEND_OP_REVERSE_SUBTRACT;
    case BlendOp::Min:
      return VK_BLEND_OP_MIN;
    case BlendOp::Max:
      return VK_BLEND_OP_MAX;
  }
  return VK_BLEND_OP_ADD;
}

VkDescriptorType toVk(BindingKind k) {
  switch (k) {
    case BindingKind::UniformBuffer:
      return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingKind::StorageBuffer:
      return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingKind::SampledTexture:
      return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  }
  return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

struct BufferRes {
  BufferDesc desc;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;  // allocated size (>= desc.bytes, multiple of 4, at least 4)
};

struct TextureRes {
  TextureDesc desc;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  bool linear = false;  // sampler actually used (linear may fall back to nearest)
};

struct PipelineRes {
  std::string name;
  bool compute = false;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  std::vector<BindingSlot> bindings;
  std::vector<Format> colorFormats;
  bool hasDepth = false;
};

struct HostBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
};

struct CurrentPass {
  std::string name;
  std::vector<uint32_t> sampled;
  std::vector<Format> colorFormats;
  bool hasDepth = false;
  uint32_t width = 0, height = 0;
  VkPipeline boundPipeline = VK_NULL_HANDLE;
};

class VulkanDevice final : public Device {
 public:
  explicit VulkanDevice(const DeviceOptions& opts) {
    try {
      init(opts.validation || envFlag("SB_VALIDATION"));
    } catch (...) {
      cleanup();
      throw;
    }
  }
  ~VulkanDevice() override { cleanup(); }
  VulkanDevice(const VulkanDevice&) = delete;
  VulkanDevice& operator=(const VulkanDevice&) = delete;

  DeviceInfo info() const override { return info_; }

  Buffer createBuffer(const BufferDesc& desc, const void* data) override {
    BufferRes r;
    r.desc = desc;
    r.size = std::max<VkDeviceSize>(4, (desc.bytes + 3) / 4 * 4);
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = r.size;
    // Both uniform and storage usage: GL buffers are untyped, so are these.
    ci.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vkCreateBuffer(device_, &ci, nullptr, &r.buffer), "vkCreateBuffer");
    try {
      VkMemoryRequirements req;
      vkGetBufferMemoryRequirements(device_, r.buffer, &req);
      r.memory = allocate(req, false, "buffer " + desc.name);
      check(vkBindBufferMemory(device_, r.buffer, r.memory, 0), "vkBindBufferMemory");
      // Defined contents (zero) unless data is given, like a fresh GL buffer store.
      HostBuffer staging;
      if (data != nullptr && desc.bytes > 0) {
        staging = createHostBuffer(desc.bytes);
        std::memcpy(staging.mapped, data, desc.bytes);
      }
      immediate([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, r.buffer, 0, VK_WHOLE_SIZE, 0);
        if (staging.buffer != VK_NULL_HANDLE) {
          fullBarrier(cmd);
          VkBufferCopy region{0, 0, desc.bytes};
          vkCmdCopyBuffer(cmd, staging.buffer, r.buffer, 1, &region);
        }
      });
      destroyHostBuffer(staging);
    } catch (...) {
      vkDestroyBuffer(device_, r.buffer, nullptr);
      if (r.memory != VK_NULL_HANDLE) vkFreeMemory(device_, r.memory, nullptr);
      throw;
    }
    const uint32_t id = nextId_++;
    buffers_.emplace(id, r);
    return Buffer{id};
  }

  void updateBuffer(Buffer b, const void* data, std::size_t bytes, std::size_t offset) override {
    BufferRes& r = buffer(b, "updateBuffer");
    if (offset + bytes > r.desc.bytes) {
      throw DeviceError("updateBuffer: " + std::to_string(bytes) + " bytes at offset " +
                        std::to_string(offset) + " exceed buffer '" + r.desc.name + "' (" +
                        std::to_string(r.desc.bytes) + " bytes)");
    }
    if (inPass_) {
      throw DeviceError("updateBuffer('" + r.desc.name + "') inside pass '" + pass_.name +
                        "': buffers may only be updated between passes");
    }
    if (bytes == 0) return;
    if (!inFrame_) {
      HostBuffer staging = createHostBuffer(bytes);
      std::memcpy(staging.mapped, data, bytes);
      try {
        immediate([&](VkCommandBuffer cmd) {
          VkBufferCopy region{0, offset, bytes};
          vkCmdCopyBuffer(cmd, staging.buffer, r.buffer, 1, &region);
        });
      } catch (...) {
        destroyHostBuffer(staging);
        throw;
      }
      destroyHostBuffer(staging);
      return;
    }
    // Inside a frame: ordered with the recorded work. The barrier orders this
    // write after earlier reads; the next pass's barrier orders later reads.
    fullBarrier(frameCmd_);
    if (bytes <= kMaxCmdUpdateBytes && bytes % 4 == 0 && offset % 4 == 0) {
      vkCmdUpdateBuffer(frameCmd_, r.buffer, offset, bytes, data);
    } else {
      HostBuffer staging = createHostBuffer(bytes);
      frameStaging_.push_back(staging);
      std::memcpy(staging.mapped, data, bytes);
      VkBufferCopy region{0, offset, bytes};
      vkCmdCopyBuffer(frameCmd_, staging.buffer, r.buffer, 1, &region);
    }
  }

  void fillBuffer(Buffer b, uint32_t value) override {
    BufferRes& r = buffer(b, "fillBuffer");
    if (inPass_) {
      throw DeviceError("fillBuffer('" + r.desc.name + "') inside pass '" + pass_.name +
                        "': buffers may only be filled between passes");
    }
    if (!inFrame_) {
      immediate(
          [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, r.buffer, 0, VK_WHOLE_SIZE, value); });
      return;
    }
    fullBarrier(frameCmd_);
    vkCmdFillBuffer(frameCmd_, r.buffer, 0, VK_WHOLE_SIZE, value);
  }

  Texture createTexture(const TextureDesc& desc) override {
    if (desc.width == 0 || desc.height == 0) {
      throw DeviceError("createTexture('" + desc.name + "'): zero size");
    }
    TextureRes t;
    t.desc = desc;
    t.format = toVkFormat(desc.format);
    const bool depth = isDepthFormat(desc.format);
    t.aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;

    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(physical_, t.format, &fp);
    const VkFormatFeatureFlags have = fp.optimalTilingFeatures;
    const VkFormatFeatureFlags need = (depth ? VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT
                                             : VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) |
                                      VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                      VK_FORMAT_FEATURE_TRANSFER_SRC_BIT |
                                      VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    if ((have & need) != need) {
      throw DeviceError(std::string("createTexture('") + desc.name + "'): format " +
                        formatName(desc.format) +
                        " cannot be a render target, sampled and copied on " + info_.device);
    }
    t.linear = desc.linearFilter;
    if (t.linear && (isIntegerFormat(desc.format) ||
                     (have & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) == 0)) {
      std::fprintf(stderr,
                   "strandbench: vulkan: texture '%s' (%s) cannot be filtered linearly on this "
                   "device; sampling it nearest\n",
                   desc.name.c_str(), formatName(desc.format));
      t.linear = false;
    }

    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = t.format;
    ci.extent = {desc.width, desc.height, 1};
    ci.mipLevels = 1;
    ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                      : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
               VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (!depth && (have & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0) {
      ci.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
    }
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check(vkCreateImage(device_, &ci, nullptr, &t.image), "vkCreateImage");
    try {
      VkMemoryRequirements req;
      vkGetImageMemoryRequirements(device_, t.image, &req);
      t.memory = allocate(req, false, "texture " + desc.name);
      check(vkBindImageMemory(device_, t.image, t.memory, 0), "vkBindImageMemory");
      VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
      vi.image = t.image;
      vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
      vi.format = t.format;
      vi.subresourceRange = {t.aspect, 0, 1, 0, 1};
      check(vkCreateImageView(device_, &vi, nullptr, &t.view), "vkCreateImageView");
      // Defined initial contents: colour 0, depth 1 (far). A fresh resource, so an
      // immediate submission is ordered correctly even inside a frame.
      immediate([&](VkCommandBuffer cmd) {
        std::vector<VkImageMemoryBarrier> barriers;
        transition(barriers, t, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        fullBarrier(cmd, barriers);
        VkImageSubresourceRange range{t.aspect, 0, 1, 0, 1};
        if (depth) {
          VkClearDepthStencilValue v{1.0f, 0};
          vkCmdClearDepthStencilImage(cmd, t.image, t.layout, &v, 1, &range);
        } else {
          VkClearColorValue v{};
          vkCmdClearColorImage(cmd, t.image, t.layout, &v, 1, &range);
        }
      });
    } catch (...) {
      if (t.view != VK_NULL_HANDLE) vkDestroyImageView(device_, t.view, nullptr);
      vkDestroyImage(device_, t.image, nullptr);
      if (t.memory != VK_NULL_HANDLE) vkFreeMemory(device_, t.memory, nullptr);
      throw;
    }
    const uint32_t id = nextId_++;
    textures_.emplace(id, t);
    return Texture{id};
  }

  Pipeline createPipeline(const PipelineDesc& desc) override {
    const bool compute = desc.compute != nullptr;
    if (compute == (desc.vertex != nullptr || desc.fragment != nullptr) ||
        (!compute && (desc.vertex == nullptr || desc.fragment == nullptr))) {
      throw DeviceError("createPipeline('" + desc.name + "', technique '" + desc.technique +
                        "'): give either vertex+fragment or compute shaders");
    }
    if (!compute && desc.hasDepth && !isDepthFormat(desc.depthFormat)) {
      throw DeviceError("createPipeline('" + desc.name + "'): depthFormat is not a depth format");
    }
    for (Format f : desc.colorFormats) {
      if (isDepthFormat(f)) {
        throw DeviceError("createPipeline('" + desc.name + "'): depth format as colour target");
      }
    }
    for (std::size_t i = 0; i < desc.bindings.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (desc.bindings[i].binding == desc.bindings[j].binding) {
          throw DeviceError("createPipeline('" + desc.name + "'): binding " +
                            std::to_string(desc.bindings[i].binding) + " declared twice");
        }
      }
    }
    // Compile first: errors throw before any Vulkan object exists.
    std::vector<uint32_t> csSpv, vsSpv, fsSpv;
    if (compute) {
      csSpv = compileVulkanSpirv(*desc.compute, ShaderStage::Compute, desc.technique);
    } else {
      vsSpv = compileVulkanSpirv(*desc.vertex, ShaderStage::Vertex, desc.technique);
      fsSpv = compileVulkanSpirv(*desc.fragment, ShaderStage::Fragment, desc.technique);
    }

    PipelineRes p;
    p.name = desc.name;
    p.compute = compute;
    p.bindings = desc.bindings;
    p.colorFormats = desc.colorFormats;
    p.hasDepth = desc.hasDepth;
    std::vector<VkShaderModule> modules;
    auto destroyModules = [&] {
      for (VkShaderModule m : modules) vkDestroyShaderModule(device_, m, nullptr);
      modules.clear();
    };
    try {
      std::vector<VkDescriptorSetLayoutBinding> lb;
      for (const BindingSlot& s : desc.bindings) {
        lb.push_back({s.binding, toVk(s.kind), 1, VK_SHADER_STAGE_ALL, nullptr});
      }
      VkDescriptorSetLayoutCreateInfo dl{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
      dl.bindingCount = static_cast<uint32_t>(lb.size());
      dl.pBindings = lb.data();
      check(vkCreateDescriptorSetLayout(device_, &dl, nullptr, &p.setLayout),
            "vkCreateDescriptorSetLayout");
      VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
      pl.setLayoutCount = 1;
      pl.pSetLayouts = &p.setLayout;
      check(vkCreatePipelineLayout(device_, &pl, nullptr, &p.layout), "vkCreatePipelineLayout");

      auto makeModule = [&](const std::vector<uint32_t>& spv) {
        VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        mi.codeSize = spv.size() * sizeof(uint32_t);
        mi.pCode = spv.data();
        VkShaderModule m = VK_NULL_HANDLE;
        check(vkCreateShaderModule(device_, &mi, nullptr, &m), "vkCreateShaderModule");
        modules.push_back(m);
        return m;
      };

      if (compute) {
        VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        ci.stage.module = makeModule(csSpv);
        ci.stage.pName = "main";
        ci.layout = p.layout;
        check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline),
              "vkCreateComputePipelines");
      } else {
        createGraphicsPipeline(desc, p, makeModule(vsSpv), makeModule(fsSpv));
      }
      destroyModules();
    } catch (...) {
      destroyModules();
      destroyPipelineRes(p);
      throw;
    }
    const uint32_t id = nextId_++;
    pipelines_.emplace(id, p);
    return Pipeline{id};
  }

  void destroy(Buffer b) override {
    if (!b) return;
    auto it = buffers_.find(b.id);
    if (it == buffers_.end())
      throw DeviceError("destroy: unknown buffer id " + std::to_string(b.id));
    if (inFrame_) {
      deadBuffers_.push_back(it->second);  // recorded work may still use it
    } else {
      destroyBufferRes(it->second);
    }
    buffers_.erase(it);
  }

  void destroy(Texture t) override {
    if (!t) return;
    auto it = textures_.find(t.id);
    if (it == textures_.end()) {
      throw DeviceError("destroy: unknown texture id " + std::to_string(t.id));
    }
    if (inFrame_) {
      deadTextures_.push_back(it->second);
    } else {
      destroyTextureRes(it->second);
    }
    textures_.erase(it);
  }

  void beginFrame() override {
    if (inFrame_) throw DeviceError("beginFrame: a frame is already being recorded");
    check(vkResetCommandBuffer(frameCmd_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(frameCmd_, &bi), "vkBeginCommandBuffer");
    inFrame_ = true;
    passNames_.clear();
    passQueries_.clear();
    cpuMs_.clear();
    timings_.clear();
    queryCount_ = 0;
    queryPoolsReset_ = 0;
  }

  void beginPass(const PassDesc& pd) override {
    if (!inFrame_) throw DeviceError("beginPass('" + pd.name + "'): outside a frame");
    if (inPass_) {
      throw DeviceError("beginPass('" + pd.name + "'): pass '" + pass_.name + "' is still open");
    }
    CurrentPass cp;
    cp.name = pd.name;
    std::vector<uint32_t> attachments;
    auto size = [&](const TextureRes& t) {
      if (cp.width == 0) {
        cp.width = t.desc.width;
        cp.height = t.desc.height;
      } else if (cp.width != t.desc.width || cp.height != t.desc.height) {
        throw DeviceError("beginPass('" + pd.name + "'): attachments differ in size");
      }
    };
    for (const ColorAttachment& a : pd.color) {
      TextureRes& t = texture(a.texture, "beginPass");
      if (isDepthFormat(t.desc.format)) {
        throw DeviceError("beginPass('" + pd.name + "'): depth texture '" + t.desc.name +
                          "' as colour attachment");
      }
      size(t);
      cp.colorFormats.push_back(t.desc.format);
      attachments.push_back(a.texture.id);
    }
    if (pd.depth.texture) {
      TextureRes& t = texture(pd.depth.texture, "beginPass");
      if (!isDepthFormat(t.desc.format)) {
        throw DeviceError("beginPass('" + pd.name + "'): '" + t.desc.name +
                          "' is not a depth texture");
      }
      size(t);
      cp.hasDepth = true;
      attachments.push_back(pd.depth.texture.id);
    }
    if (attachments.empty()) {
      if (pd.width == 0 || pd.height == 0)
        throw DeviceError("beginPass('" + pd.name + "'): no attachments and no size");
      cp.width = pd.width;
      cp.height = pd.height;
    }
    for (Texture s : pd.sampledTextures) {
      texture(s, "beginPass");
      if (std::find(attachments.begin(), attachments.end(), s.id) != attachments.end()) {
        throw DeviceError("beginPass('" + pd.name + "'): texture '" + textures_[s.id].desc.name +
                          "' is both an attachment and sampled");
      }
      cp.sampled.push_back(s.id);
    }

    if (cpuTiming_) flushFrame();
    std::vector<VkImageMemoryBarrier> barriers;
    for (const ColorAttachment& a : pd.color) {
      transition(barriers, textures_[a.texture.id], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    }
    if (pd.depth.texture) {
      transition(barriers, textures_[pd.depth.texture.id],
                 VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    }
    for (uint32_t id : cp.sampled) {
      transition(barriers, textures_[id], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
    fullBarrier(frameCmd_, barriers);
    beginTiming(pd.name);

    std::vector<VkRenderingAttachmentInfo> colors;
    for (const ColorAttachment& a : pd.color) {
      const TextureRes& t = textures_[a.texture.id];
      VkRenderingAttachmentInfo ai{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
      ai.imageView = t.view;
      ai.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      ai.loadOp =
          a.load == LoadOp::Clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
      ai.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      if (isIntegerFormat(t.desc.format)) {
        for (int i = 0; i < 4; ++i) ai.clearValue.color.uint32[i] = a.clearUint[i];
      } else {
        for (int i = 0; i < 4; ++i) ai.clearValue.color.float32[i] = a.clear[i];
      }
      colors.push_back(ai);
    }
    VkRenderingAttachmentInfo depthInfo{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    if (pd.depth.texture) {
      depthInfo.imageView = textures_[pd.depth.texture.id].view;
      depthInfo.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
      depthInfo.loadOp =
          pd.depth.load == LoadOp::Clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
      depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      depthInfo.clearValue.depthStencil = {pd.depth.clear, 0};
    }
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {cp.width, cp.height}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = static_cast<uint32_t>(colors.size());
    ri.pColorAttachments = colors.data();
    ri.pDepthAttachment = pd.depth.texture ? &depthInfo : nullptr;
    vkCmdBeginRendering(frameCmd_, &ri);
    // Positive height: NDC y=-1 maps to framebuffer row 0 (no flip), as in GL
    // with glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE).
    VkViewport vp{0, 0, static_cast<float>(cp.width), static_cast<float>(cp.height), 0, 1};
    VkRect2D sc{{0, 0}, {cp.width, cp.height}};
    vkCmdSetViewport(frameCmd_, 0, 1, &vp);
    vkCmdSetScissor(frameCmd_, 0, 1, &sc);
    pass_ = std::move(cp);
    inPass_ = true;
  }

  void draw(Pipeline pipe, const std::vector<Binding>& bindings, uint32_t vertexCount,
            uint32_t instanceCount) override {
    if (!inPass_) throw DeviceError("draw: outside a pass");
    PipelineRes& p = pipeline(pipe, "draw");
    if (p.compute) throw DeviceError("draw: '" + p.name + "' is a compute pipeline");
    if (p.colorFormats != pass_.colorFormats || p.hasDepth != pass_.hasDepth) {
      throw DeviceError("draw: pipeline '" + p.name + "' targets do not match pass '" + pass_.name +
                        "' (colour formats and depth must be the same)");
    }
    VkDescriptorSet set = makeSet(p, bindings, true);
    if (pass_.boundPipeline != p.pipeline) {
      vkCmdBindPipeline(frameCmd_, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipeline);
      pass_.boundPipeline = p.pipeline;
    }
    if (set != VK_NULL_HANDLE) {
      vkCmdBindDescriptorSets(frameCmd_, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 0, 1, &set, 0,
                              nullptr);
    }
    if (vertexCount > 0 && instanceCount > 0) {
      vkCmdDraw(frameCmd_, vertexCount, instanceCount, 0, 0);
    }
  }

  void endPass() override {
    if (!inPass_) throw DeviceError("endPass: no pass is open");
    vkCmdEndRendering(frameCmd_);
    inPass_ = false;
    endTiming();
  }

  void dispatch(const std::string& passName, Pipeline pipe, const std::vector<Binding>& bindings,
                uint32_t x, uint32_t y, uint32_t z) override {
    if (!inFrame_) throw DeviceError("dispatch('" + passName + "'): outside a frame");
    if (inPass_) {
      throw DeviceError("dispatch('" + passName + "'): inside pass '" + pass_.name + "'");
    }
    PipelineRes& p = pipeline(pipe, "dispatch");
    if (!p.compute) throw DeviceError("dispatch: '" + p.name + "' is not a compute pipeline");
    for (const Binding& b : bindings) {
      if (b.texture) texture(b.texture, "dispatch");
    }
    if (cpuTiming_) flushFrame();
    std::vector<VkImageMemoryBarrier> barriers;
    for (const Binding& b : bindings) {
      if (b.texture) {
        transition(barriers, textures_[b.texture.id], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
      }
    }
    VkDescriptorSet set = makeSet(p, bindings, false);
    fullBarrier(frameCmd_, barriers);
    beginTiming(passName);
    vkCmdBindPipeline(frameCmd_, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
    if (set != VK_NULL_HANDLE) {
      vkCmdBindDescriptorSets(frameCmd_, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &set, 0,
                              nullptr);
    }
    if (x > 0 && y > 0 && z > 0) vkCmdDispatch(frameCmd_, x, y, z);
    endTiming();
  }

  void endFrame() override {
    if (!inFrame_) throw DeviceError("endFrame: no frame is being recorded");
    if (inPass_) throw DeviceError("endFrame: pass '" + pass_.name + "' is still open");
    inFrame_ = false;  // whatever happens below, the frame is over
    struct FrameCleanup {
      VulkanDevice* d;
      ~FrameCleanup() { d->finishFrameResources(); }
    } frameCleanup{this};
    fullBarrier(frameCmd_);
    check(vkEndCommandBuffer(frameCmd_), "vkEndCommandBuffer");
    submitAndWait(frameCmd_);

    timings_.clear();
    if (cpuTiming_) {
      for (std::size_t i = 0; i < passNames_.size(); ++i) {
        timings_.push_back({passNames_[i], i < cpuMs_.size() ? cpuMs_[i] : 0.0});
      }
      return;
    }
    std::vector<uint64_t> stamps(queryCount_);
    for (uint32_t pool = 0; pool * kQueriesPerPool < queryCount_; ++pool) {
      const uint32_t first = pool * kQueriesPerPool;
      const uint32_t count = std::min(kQueriesPerPool, queryCount_ - first);
      check(vkGetQueryPoolResults(device_, queryPools_[pool], 0, count, count * sizeof(uint64_t),
                                  stamps.data() + first, sizeof(uint64_t),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults");
    }
    const uint64_t mask =
        timestampBits_ >= 64 ? ~uint64_t{0} : ((uint64_t{1} << timestampBits_) - 1);
    for (std::size_t i = 0; i < passNames_.size(); ++i) {
      const uint32_t q = passQueries_[i];
      const uint64_t ticks = (stamps[q + 1] - stamps[q]) & mask;
      timings_.push_back({passNames_[i], static_cast<double>(ticks) * timestampPeriod_ / 1e6});
    }
  }

  std::vector<PassTiming> lastFrameTimings() const override { return timings_; }

  TextureDesc describe(Texture t) const override {
    auto it = textures_.find(t.id);
    if (it == textures_.end()) throw DeviceError("describe: unknown texture");
    return it->second.desc;
  }

  std::vector<uint8_t> readTexture(Texture tex) override {
    TextureRes& t = texture(tex, "readTexture");
    if (inFrame_) throw DeviceError("readTexture('" + t.desc.name + "'): only after endFrame()");
    const std::size_t bytes =
        std::size_t{t.desc.width} * t.desc.height * bytesPerPixel(t.desc.format);
    HostBuffer staging = createHostBuffer(bytes);
    std::vector<uint8_t> out(bytes);
    try {
      immediate([&](VkCommandBuffer cmd) {
        std::vector<VkImageMemoryBarrier> barriers;
        transition(barriers, t, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        fullBarrier(cmd, barriers);
        VkBufferImageCopy region{};
        region.imageSubresource = {t.aspect, 0, 0, 1};
        region.imageExtent = {t.desc.width, t.desc.height, 1};
        vkCmdCopyImageToBuffer(cmd, t.image, t.layout, staging.buffer, 1, &region);
        hostReadBarrier(cmd);
      });
      std::memcpy(out.data(), staging.mapped, bytes);
    } catch (...) {
      destroyHostBuffer(staging);
      throw;
    }
    destroyHostBuffer(staging);
    return out;
  }

  std::vector<uint8_t> readBuffer(Buffer b) override {
    BufferRes& r = buffer(b, "readBuffer");
    if (inFrame_) throw DeviceError("readBuffer('" + r.desc.name + "'): only after endFrame()");
    std::vector<uint8_t> out(r.desc.bytes);
    if (out.empty()) return out;
    HostBuffer staging = createHostBuffer(r.desc.bytes);
    try {
      immediate([&](VkCommandBuffer cmd) {
        fullBarrier(cmd);
        VkBufferCopy region{0, 0, r.desc.bytes};
        vkCmdCopyBuffer(cmd, r.buffer, staging.buffer, 1, &region);
        hostReadBarrier(cmd);
      });
      std::memcpy(out.data(), staging.mapped, out.size());
    } catch (...) {
      destroyHostBuffer(staging);
      throw;
    }
    destroyHostBuffer(staging);
    return out;
  }

  std::vector<ResourceBytes> allocations() const override {
    // Ids are shared by all kinds, so sorting by id gives creation order.
    std::vector<std::pair<uint32_t, ResourceBytes>> all;
    for (const auto& [id, r] : buffers_)
      all.push_back({id, {r.desc.name, r.desc.owner, r.desc.bytes}});
    for (const auto& [id, t] : textures_) {
      all.push_back({id,
                     {t.desc.name, t.desc.owner,
                      std::size_t{t.desc.width} * t.desc.height * bytesPerPixel(t.desc.format)}});
    }
    std::sort(all.begin(), all.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<ResourceBytes> out;
    for (auto& [id, r] : all) out.push_back(std::move(r));
    return out;
  }

 private:
  // ---- setup and teardown ----
  void init(bool validation) {
    createInstance(validation);
    pickPhysicalDevice();
    createLogicalDevice();

    VkCommandPoolCreateInfo cp{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    cp.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    cp.queueFamilyIndex = queueFamily_;
    check(vkCreateCommandPool(device_, &cp, nullptr, &cmdPool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ca{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ca.commandPool = cmdPool_;
    ca.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ca.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(device_, &ca, &frameCmd_), "vkAllocateCommandBuffers");
    check(vkAllocateCommandBuffers(device_, &ca, &immCmd_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(device_, &fi, nullptr, &fence_), "vkCreateFence");

    for (int linear = 0; linear < 2; ++linear) {
      VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
      si.magFilter = si.minFilter = linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
      si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
      si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
      si.minLod = 0;
      si.maxLod = 0;
      si.unnormalizedCoordinates = VK_FALSE;
      check(vkCreateSampler(device_, &si, nullptr, &samplers_[linear]), "vkCreateSampler");
    }
  }

  void createInstance(bool validation) {
    uint32_t loaderVersion = VK_API_VERSION_1_0;
    if (vkEnumerateInstanceVersion(&loaderVersion) != VK_SUCCESS ||
        loaderVersion < VK_API_VERSION_1_3) {
      throw DeviceError("no Vulkan device found: the Vulkan loader supports only version " +
                        versionString(loaderVersion) + "; 1.3 is required");
    }
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
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
    VkResult r = vkCreateInstance(&ci, nullptr, &instance_);
    if (r != VK_SUCCESS) {
      instance_ = VK_NULL_HANDLE;
      throw DeviceError(std::string("no Vulkan device found: vkCreateInstance failed with ") +
                        resultName(r) +
                        " (is a Vulkan driver such as mesa-vulkan-drivers "
                        "installed?)");
    }
    if (debugUtils) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
      if (create != nullptr) {
        check(create(instance_, &dbg, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
      }
    }
  }

  static std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
  }

  void pickPhysicalDevice() {
    uint32_t n = 0;
    VkResult r = vkEnumeratePhysicalDevices(instance_, &n, nullptr);
    if (r != VK_SUCCESS || n == 0) {
      throw DeviceError(
          "no Vulkan device found: no physical device (install a Vulkan driver, e.g. "
          "mesa-vulkan-drivers for lavapipe)");
    }
    std::vector<VkPhysicalDevice> devs(n);
    check(vkEnumeratePhysicalDevices(instance_, &n, devs.data()), "vkEnumeratePhysicalDevices");
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
      for (uint32_t i = 0; i < qn; ++i) {
        if ((qs[i].queueFlags & want) == want) {
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
            "no Vulkan device found with Vulkan 1.3, dynamic rendering and a graphics+compute "
            "queue (devices: " +
            seen + ")");
      }
    }
    physical_ = pick->pd;
    queueFamily_ = pick->family;
    limits_ = pick->props.limits;
    timestampPeriod_ = pick->props.limits.timestampPeriod;

    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> qs(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, qs.data());
    timestampBits_ = qs[queueFamily_].timestampValidBits;
    // lavapipe writes a pass's end timestamp before llvmpipe has finished
    // rasterizing it (measured: 0.6 ms by timestamps vs 33 ms by wall clock for
    // a 30k-segment pass), so CPU devices are timed per pass on the CPU, as GL is.
    cpuTiming_ =
        timestampBits_ == 0 || envFlag("SB_VULKAN_CPU_TIMING") ||
        (pick->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU && !envFlag("SB_VULKAN_GPU_TIMING"));

    VkPhysicalDeviceDriverProperties drv{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &drv};
    vkGetPhysicalDeviceProperties2(physical_, &p2);
    info_.backend = "vulkan";
    info_.timing = cpuTiming_ ? "cpu clock per pass (submit and wait)" : "gpu timestamps";
    info_.platform = "headless";
    info_.device = pick->props.deviceName;
    if (drv.driverName[0] != '\0') {
      info_.driver = std::string(drv.driverName) + " " + drv.driverInfo;
    } else {
      info_.driver = "driver version " + std::to_string(pick->props.driverVersion) + ", Vulkan " +
                     versionString(pick->props.apiVersion);
    }
  }

  void createLogicalDevice() {
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(physical_, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> exts(n);
    vkEnumerateDeviceExtensionProperties(physical_, nullptr, &n, exts.data());
    const bool haveLineExt = std::any_of(exts.begin(), exts.end(), [](const auto& x) {
      return std::strcmp(x.extensionName, VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME) == 0;
    });

    // Enable every supported core feature (the techniques' shaders may use image
    // or int64 atomics, logic op, independent blend...), except robustness, which
    // only costs speed, and sparse/protected features, which need more setup.
    VkPhysicalDeviceLineRasterizationFeaturesEXT line{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT};
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                         haveLineExt ? &line : nullptr};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                         &f13};
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES,
                                         &f12};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11};
    vkGetPhysicalDeviceFeatures2(physical_, &f2);
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
    logicOp_ = f2.features.logicOp == VK_TRUE;
    // SB_VULKAN_LINES=default keeps the API's default (rectangular) lines, to
    // measure how far they are from GL's aliased lines.
    const char* linesEnv = std::getenv("SB_VULKAN_LINES");
    const bool wantBresenham = !(linesEnv && std::string(linesEnv) == "default");
    bresenham_ = wantBresenham && haveLineExt && line.bresenhamLines == VK_TRUE;
    info_.lines = bresenham_ ? "bresenham (VK_EXT_line_rasterization)" : "default (rectangular)";
    line.rectangularLines = VK_FALSE;
    line.smoothLines = VK_FALSE;
    line.stippledRectangularLines = VK_FALSE;
    line.stippledBresenhamLines = VK_FALSE;
    line.stippledSmoothLines = VK_FALSE;
    line.bresenhamLines = bresenham_ ? VK_TRUE : VK_FALSE;

    std::vector<const char*> enabled;
    if (bresenham_) enabled.push_back(VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME);
    if (!bresenham_) f13.pNext = nullptr;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qi.queueFamilyIndex = queueFamily_;
    qi.queueCount = 1;
    qi.pQueuePriorities = &priority;
    VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &f2};
    ci.queueCreateInfoCount = 1;
    ci.pQueueCreateInfos = &qi;
    ci.enabledExtensionCount = static_cast<uint32_t>(enabled.size());
    ci.ppEnabledExtensionNames = enabled.data();
    check(vkCreateDevice(physical_, &ci, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memProps_);
  }

  void cleanup() {
    if (device_ != VK_NULL_HANDLE) {
      vkDeviceWaitIdle(device_);
      finishFrameResources();
      for (auto& [id, p] : pipelines_) destroyPipelineRes(p);
      pipelines_.clear();
      for (auto& [id, t] : textures_) destroyTextureRes(t);
      textures_.clear();
      for (auto& [id, b] : buffers_) destroyBufferRes(b);
      buffers_.clear();
      for (VkDescriptorPool p : descPools_) vkDestroyDescriptorPool(device_, p, nullptr);
      descPools_.clear();
      for (VkQueryPool q : queryPools_) vkDestroyQueryPool(device_, q, nullptr);
      queryPools_.clear();
      for (VkSampler& s : samplers_) {
        if (s != VK_NULL_HANDLE) vkDestroySampler(device_, s, nullptr);
        s = VK_NULL_HANDLE;
      }
      if (fence_ != VK_NULL_HANDLE) vkDestroyFence(device_, fence_, nullptr);
      if (cmdPool_ != VK_NULL_HANDLE) vkDestroyCommandPool(device_, cmdPool_, nullptr);
      vkDestroyDevice(device_, nullptr);
      device_ = VK_NULL_HANDLE;
    }
    if (messenger_ != VK_NULL_HANDLE) {
      auto destroyFn = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
      if (destroyFn != nullptr) destroyFn(instance_, messenger_, nullptr);
      messenger_ = VK_NULL_HANDLE;
    }
    if (instance_ != VK_NULL_HANDLE) {
      vkDestroyInstance(instance_, nullptr);
      instance_ = VK_NULL_HANDLE;
    }
  }

  // ---- resources ----
  BufferRes& buffer(Buffer b, const char* op) {
    auto it = buffers_.find(b.id);
    if (it == buffers_.end()) {
      throw DeviceError(std::string(op) + ": unknown buffer id " + std::to_string(b.id));
    }
    return it->second;
  }
  TextureRes& texture(Texture t, const char* op) {
    auto it = textures_.find(t.id);
    if (it == textures_.end()) {
      throw DeviceError(std::string(op) + ": unknown texture id " + std::to_string(t.id));
    }
    return it->second;
  }
  PipelineRes& pipeline(Pipeline p, const char* op) {
    auto it = pipelines_.find(p.id);
    if (it == pipelines_.end()) {
      throw DeviceError(std::string(op) + ": unknown pipeline id " + std::to_string(p.id));
    }
    return it->second;
  }

  VkDeviceMemory allocate(const VkMemoryRequirements& req, bool host, const std::string& what) {
    const VkMemoryPropertyFlags want =
        host ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
             : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < memProps_.memoryTypeCount && type == UINT32_MAX; ++i) {
      if ((req.memoryTypeBits & (1u << i)) != 0 &&
          (memProps_.memoryTypes[i].propertyFlags & want) == want) {
        type = i;
      }
    }
    if (type == UINT32_MAX && !host) {  // no device-local type fits: take any
      for (uint32_t i = 0; i < memProps_.memoryTypeCount && type == UINT32_MAX; ++i) {
        if ((req.memoryTypeBits & (1u << i)) != 0) type = i;
      }
    }
    if (type == UINT32_MAX) throw DeviceError("vulkan: no memory type for " + what);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = type;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    VkResult r = vkAllocateMemory(device_, &ai, nullptr, &mem);
    if (r != VK_SUCCESS) {
      throw DeviceError("vulkan: allocating " + std::to_string(req.size) + " bytes for " + what +
                        " failed: " + resultName(r));
    }
    return mem;
  }

  HostBuffer createHostBuffer(VkDeviceSize bytes) {
    HostBuffer h;
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = std::max<VkDeviceSize>(bytes, 4);
    ci.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vkCreateBuffer(device_, &ci, nullptr, &h.buffer), "vkCreateBuffer (staging)");
    try {
      VkMemoryRequirements req;
      vkGetBufferMemoryRequirements(device_, h.buffer, &req);
      h.memory = allocate(req, true, "staging buffer");
      check(vkBindBufferMemory(device_, h.buffer, h.memory, 0), "vkBindBufferMemory (staging)");
      check(vkMapMemory(device_, h.memory, 0, VK_WHOLE_SIZE, 0, &h.mapped), "vkMapMemory");
    } catch (...) {
      destroyHostBuffer(h);
      throw;
    }
    return h;
  }

  void destroyHostBuffer(HostBuffer& h) {
    if (h.buffer != VK_NULL_HANDLE) vkDestroyBuffer(device_, h.buffer, nullptr);
    if (h.memory != VK_NULL_HANDLE) vkFreeMemory(device_, h.memory, nullptr);  // unmaps
    h = HostBuffer{};
  }

  void destroyBufferRes(BufferRes& b) {
    if (b.buffer != VK_NULL_HANDLE) vkDestroyBuffer(device_, b.buffer, nullptr);
    if (b.memory != VK_NULL_HANDLE) vkFreeMemory(device_, b.memory, nullptr);
    b.buffer = VK_NULL_HANDLE;
    b.memory = VK_NULL_HANDLE;
  }

  void destroyTextureRes(TextureRes& t) {
    if (t.view != VK_NULL_HANDLE) vkDestroyImageView(device_, t.view, nullptr);
    if (t.image != VK_NULL_HANDLE) vkDestroyImage(device_, t.image, nullptr);
    if (t.memory != VK_NULL_HANDLE) vkFreeMemory(device_, t.memory, nullptr);
    t.view = VK_NULL_HANDLE;
    t.image = VK_NULL_HANDLE;
    t.memory = VK_NULL_HANDLE;
  }

  void destroyPipelineRes(PipelineRes& p) {
    if (p.pipeline != VK_NULL_HANDLE) vkDestroyPipeline(device_, p.pipeline, nullptr);
    if (p.layout != VK_NULL_HANDLE) vkDestroyPipelineLayout(device_, p.layout, nullptr);
    if (p.setLayout != VK_NULL_HANDLE) {
      vkDestroyDescriptorSetLayout(device_, p.setLayout, nullptr);
    }
    p.pipeline = VK_NULL_HANDLE;
    p.layout = VK_NULL_HANDLE;
    p.setLayout = VK_NULL_HANDLE;
  }

  // Frees what a frame kept alive (staging, destroyed resources) and resets the
  // descriptor pools. Called once the frame's work is complete (or abandoned).
  void finishFrameResources() {
    for (HostBuffer& h : frameStaging_) destroyHostBuffer(h);
    frameStaging_.clear();
    for (BufferRes& b : deadBuffers_) destroyBufferRes(b);
    deadBuffers_.clear();
    for (TextureRes& t : deadTextures_) destroyTextureRes(t);
    deadTextures_.clear();
    for (VkDescriptorPool p : descPools_) vkResetDescriptorPool(device_, p, 0);
    descPool_ = 0;
  }

  void createGraphicsPipeline(const PipelineDesc& desc, PipelineRes& p, VkShaderModule vs,
                              VkShaderModule fs) {
    VkPipelineShaderStageCreateInfo stages[2] = {
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs;
    stages[1].pName = "main";

    VkPipelineVertexInputStateCreateInfo vi{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo ia{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    const bool lines = desc.topology == Topology::Lines;
    ia.topology = lines ? VK_PRIMITIVE_TOPOLOGY_LINE_LIST : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vps.viewportCount = 1;
    vps.scissorCount = 1;
    VkPipelineRasterizationLineStateCreateInfoEXT lineState{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT};
    lineState.lineRasterizationMode = VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT;
    VkPipelineRasterizationStateCreateInfo rs{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.pNext = lines && bresenham_ ? &lineState : nullptr;
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = desc.hasDepth && desc.depthTest;
    ds.depthWriteEnable = desc.hasDepth && desc.depthWrite;
    ds.depthCompareOp = toVk(desc.depthCompare);

    if (desc.logicOpOr && !logicOp_) {
      throw DeviceError("createPipeline('" + desc.name + "', technique '" + desc.technique +
                        "'): logic-op OR needs the logicOp feature, which " + info_.device +
                        " lacks");
    }
    std::vector<VkPipelineColorBlendAttachmentState> blends;
    for (std::size_t i = 0; i < desc.colorFormats.size(); ++i) {
      const Format f = desc.colorFormats[i];
      const BlendState b = i < desc.blend.size() ? desc.blend[i] : BlendState::replace();
      VkPipelineColorBlendAttachmentState a{};
      a.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                         VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
      // Integer targets never blend; with a logic op, blending is ignored anyway.
      a.blendEnable = b.enable && !isIntegerFormat(f) && !desc.logicOpOr;
      if (a.blendEnable) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(physical_, toVkFormat(f), &fp);
        if ((fp.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT) == 0) {
          throw DeviceError("createPipeline('" + desc.name + "', technique '" + desc.technique +
                            "'): format " + formatName(f) + " cannot blend on " + info_.device);
        }
      }
      a.srcColorBlendFactor = toVk(b.srcColor);
      a.dstColorBlendFactor = toVk(b.dstColor);
      a.colorBlendOp = toVk(b.colorOp);
      a.srcAlphaBlendFactor = toVk(b.srcAlpha);
      a.dstAlphaBlendFactor = toVk(b.dstAlpha);
      a.alphaBlendOp = toVk(b.alphaOp);
      blends.push_back(a);
    }
    VkPipelineColorBlendStateCreateInfo cb{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.logicOpEnable = desc.logicOpOr ? VK_TRUE : VK_FALSE;
    cb.logicOp = VK_LOGIC_OP_OR;
    cb.attachmentCount = static_cast<uint32_t>(blends.size());
    cb.pAttachments = blends.data();

    const VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dy.dynamicStateCount = 2;
    dy.pDynamicStates = dyn;

    std::vector<VkFormat> colorFormats;
    for (Format f : desc.colorFormats) colorFormats.push_back(toVkFormat(f));
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<uint32_t>(colorFormats.size());
    rendering.pColorAttachmentFormats = colorFormats.data();
    rendering.depthAttachmentFormat =
        desc.hasDepth ? toVkFormat(desc.depthFormat) : VK_FORMAT_UNDEFINED;
    rendering.stencilAttachmentFormat = VK_FORMAT_UNDEFINED;

    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    ci.stageCount = 2;
    ci.pStages = stages;
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vps;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &ds;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &dy;
    ci.layout = p.layout;
    check(vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline),
          "vkCreateGraphicsPipelines");
  }

  // ---- recording helpers ----
  static void fullBarrier(VkCommandBuffer cmd,
                          const std::vector<VkImageMemoryBarrier>& images = {}) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &mb, 0, nullptr,
                         static_cast<uint32_t>(images.size()), images.data());
  }

  static void hostReadBarrier(VkCommandBuffer cmd) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb,
                         0, nullptr, 0, nullptr);
  }

  // Appends a layout transition (if needed) and updates the tracked layout.
  static void transition(std::vector<VkImageMemoryBarrier>& out, TextureRes& t,
                         VkImageLayout layout) {
    if (t.layout == layout) return;
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    b.oldLayout = t.layout;
    b.newLayout = layout;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = t.image;
    b.subresourceRange = {t.aspect, 0, 1, 0, 1};
    out.push_back(b);
    t.layout = layout;
  }

  template <class F>
  void immediate(F&& record) {
    check(vkResetCommandBuffer(immCmd_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(immCmd_, &bi), "vkBeginCommandBuffer");
    record(immCmd_);
    check(vkEndCommandBuffer(immCmd_), "vkEndCommandBuffer");
    submitAndWait(immCmd_);
  }

  void submitAndWait(VkCommandBuffer cmd) {
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    check(vkQueueSubmit(queue_, 1, &si, fence_), "vkQueueSubmit");
    check(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(device_, 1, &fence_), "vkResetFences");
  }

  // CPU-timing mode: submit what is recorded so far, wait, and go on recording.
  void flushFrame() {
    check(vkEndCommandBuffer(frameCmd_), "vkEndCommandBuffer");
    submitAndWait(frameCmd_);
    check(vkResetCommandBuffer(frameCmd_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(frameCmd_, &bi), "vkBeginCommandBuffer");
  }

  void beginTiming(const std::string& name) {
    passNames_.push_back(name);
    if (cpuTiming_) return;
    const uint32_t q = queryCount_;
    const uint32_t pool = q / kQueriesPerPool;
    while (queryPools_.size() <= pool) {
      VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
      qi.queryCount = kQueriesPerPool;
      VkQueryPool qp = VK_NULL_HANDLE;
      check(vkCreateQueryPool(device_, &qi, nullptr, &qp), "vkCreateQueryPool");
      queryPools_.push_back(qp);
    }
    if (pool >= queryPoolsReset_) {  // first use this frame: reset (outside rendering)
      vkCmdResetQueryPool(frameCmd_, queryPools_[pool], 0, kQueriesPerPool);
      queryPoolsReset_ = pool + 1;
    }
    vkCmdWriteTimestamp(frameCmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queryPools_[pool],
                        q % kQueriesPerPool);
    passQueries_.push_back(q);
    queryCount_ += 2;
  }

  void endTiming() {
    if (cpuTiming_) {
      const auto t0 = std::chrono::steady_clock::now();
      flushFrame();
      const auto t1 = std::chrono::steady_clock::now();
      cpuMs_.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      return;
    }
    const uint32_t q = passQueries_.back() + 1;
    vkCmdWriteTimestamp(frameCmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                        queryPools_[q / kQueriesPerPool], q % kQueriesPerPool);
  }

  VkDescriptorSet allocateSet(VkDescriptorSetLayout layout) {
    for (;;) {
      if (descPool_ == descPools_.size()) {
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1024},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2048},
                                              {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1024}};
        VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pi.maxSets = 512;
        pi.poolSizeCount = 3;
        pi.pPoolSizes = sizes;
        VkDescriptorPool pool = VK_NULL_HANDLE;
        check(vkCreateDescriptorPool(device_, &pi, nullptr, &pool), "vkCreateDescriptorPool");
        descPools_.push_back(pool);
      }
      VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
      ai.descriptorPool = descPools_[descPool_];
      ai.descriptorSetCount = 1;
      ai.pSetLayouts = &layout;
      VkDescriptorSet set = VK_NULL_HANDLE;
      VkResult r = vkAllocateDescriptorSets(device_, &ai, &set);
      if (r == VK_SUCCESS) return set;
      if (r != VK_ERROR_OUT_OF_POOL_MEMORY && r != VK_ERROR_FRAGMENTED_POOL) {
        check(r, "vkAllocateDescriptorSets");
      }
      ++descPool_;  // exhausted: move on to (or create) the next pool
    }
  }

  // Validates bindings against the pipeline's slots and writes a fresh set.
  VkDescriptorSet makeSet(const PipelineRes& p, const std::vector<Binding>& bindings,
                          bool inRenderPass) {
    const std::string where = (inRenderPass ? "draw('" : "dispatch('") + p.name + "')";
    for (const Binding& b : bindings) {
      const bool declared =
          std::any_of(p.bindings.begin(), p.bindings.end(),
                      [&](const BindingSlot& s) { return s.binding == b.binding; });
      if (!declared) {
        throw DeviceError(where + ": binding " + std::to_string(b.binding) +
                          " is not declared in the pipeline");
      }
    }
    if (p.bindings.empty()) return VK_NULL_HANDLE;
    std::vector<VkDescriptorBufferInfo> bufInfos;
    std::vector<VkDescriptorImageInfo> imgInfos;
    bufInfos.reserve(p.bindings.size());
    imgInfos.reserve(p.bindings.size());
    std::vector<VkWriteDescriptorSet> writes;
    for (const BindingSlot& s : p.bindings) {
      auto it = std::find_if(bindings.begin(), bindings.end(),
                             [&](const Binding& b) { return b.binding == s.binding; });
      if (it == bindings.end()) {
        throw DeviceError(where + ": binding " + std::to_string(s.binding) + " not provided");
      }
      VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w.dstBinding = s.binding;
      w.descriptorCount = 1;
      w.descriptorType = toVk(s.kind);
      if (s.kind == BindingKind::SampledTexture) {
        if (!it->texture) {
          throw DeviceError(where + ": binding " + std::to_string(s.binding) + " needs a texture");
        }
        const TextureRes& t = texture(it->texture, "bind");
        if (inRenderPass && std::find(pass_.sampled.begin(), pass_.sampled.end(), it->texture.id) ==
                                pass_.sampled.end()) {
          throw DeviceError(where + ": texture '" + t.desc.name + "' is sampled but pass '" +
                            pass_.name + "' does not list it in sampledTextures");
        }
        imgInfos.push_back(
            {samplers_[t.linear ? 1 : 0], t.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
        w.pImageInfo = &imgInfos.back();
      } else {
        if (!it->buffer) {
          throw DeviceError(where + ": binding " + std::to_string(s.binding) + " needs a buffer");
        }
        const BufferRes& b = buffer(it->buffer, "bind");
        const VkDeviceSize limit = s.kind == BindingKind::UniformBuffer
                                       ? limits_.maxUniformBufferRange
                                       : limits_.maxStorageBufferRange;
        bufInfos.push_back({b.buffer, 0, std::min<VkDeviceSize>(b.size, limit)});
        w.pBufferInfo = &bufInfos.back();
      }
      writes.push_back(w);
    }
    VkDescriptorSet set = allocateSet(p.setLayout);
    for (VkWriteDescriptorSet& w : writes) w.dstSet = set;
    vkUpdateDescriptorSets(device_, static_cast<uint32_t>(writes.size()), writes.data(), 0,
                           nullptr);
    return set;
  }

  // ---- state ----
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkPhysicalDeviceLimits limits_{};
  VkPhysicalDeviceMemoryProperties memProps_{};
  float timestampPeriod_ = 1.0f;
  uint32_t timestampBits_ = 0;
  bool cpuTiming_ = false;
  bool logicOp_ = false;
  bool bresenham_ = false;
  DeviceInfo info_;

  VkCommandPool cmdPool_ = VK_NULL_HANDLE;
  VkCommandBuffer frameCmd_ = VK_NULL_HANDLE;
  VkCommandBuffer immCmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSampler samplers_[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};  // nearest, linear

  uint32_t nextId_ = 1;
  std::map<uint32_t, BufferRes> buffers_;
  std::map<uint32_t, TextureRes> textures_;
  std::map<uint32_t, PipelineRes> pipelines_;

  bool inFrame_ = false;
  bool inPass_ = false;
  CurrentPass pass_;
  std::vector<HostBuffer> frameStaging_;
  std::vector<BufferRes> deadBuffers_;
  std::vector<TextureRes> deadTextures_;
  std::vector<VkDescriptorPool> descPools_;
  std::size_t descPool_ = 0;  // first pool that may still have room this frame
  std::vector<VkQueryPool> queryPools_;
  uint32_t queryCount_ = 0;
  uint32_t queryPoolsReset_ = 0;
  std::vector<std::string> passNames_;
  std::vector<uint32_t> passQueries_;
  std::vector<double> cpuMs_;
  std::vector<PassTiming> timings_;
};

}  // namespace

std::unique_ptr<Device> createVulkanDevice(const DeviceOptions& opts) {
  return std::make_unique<VulkanDevice>(opts);
}

std::size_t validationMessageCount() { return g_validationMessages.load(); }

}  // namespace sb
