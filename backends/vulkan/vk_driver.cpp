// The Vulkan driver under the Device front end (backends/device.h, driver.h).
//
// Design (simple and correct over clever):
//  - One command buffer per frame, recorded between beginFrame and endFrame;
//    endFrame submits and waits on a fence. Work outside a frame (uploads,
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
#include "backends/vulkan/vk_driver.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "backends/vulkan/vk_pipeline.h"
#include "backends/vulkan/vk_platform.h"
#include "backends/vulkan/vk_shader.h"
#include "backends/vulkan/vk_util.h"

namespace sb {

namespace {

constexpr uint32_t kQueriesPerPool = 128;  // even: a pass's pair never straddles pools
constexpr VkDeviceSize kMaxCmdUpdateBytes = 65536;

struct BufferRes : DriverObject {
  BufferDesc desc;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;  // allocated size (>= desc.bytes, multiple of 4, at least 4)
};

struct TextureRes : DriverObject {
  TextureDesc desc;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;       // 2D (one layer): attachment and sampler2D
  VkImageView arrayView = VK_NULL_HANDLE;  // 2D_ARRAY of every layer: sampler2DArray
  std::vector<VkImageView> layerViews;     // layers > 1: 2D of one layer, made when attached
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // of every layer (they move together)
  bool linear = false;  // sampler actually used (linear may fall back to nearest)
};

struct PipelineRes : DriverObject {
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
};

struct HostBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
};

class VulkanDriver final : public Driver {
 public:
  explicit VulkanDriver(std::unique_ptr<VulkanPlatform> platform) : platform_(std::move(platform)) {
    const VulkanPlatform& p = *platform_;
    device_ = p.device;
    physical_ = p.physical;
    queue_ = p.queue;
    limits_ = p.limits;
    memProps_ = p.memProps;
    timestampPeriod_ = p.timestampPeriod;
    timestampBits_ = p.timestampBits;
    cpuTiming_ = p.cpuTiming;
    try {
      createCommandObjects(p.queueFamily);
    } catch (...) {
      cleanup();
      throw;
    }
  }
  ~VulkanDriver() override { cleanup(); }
  VulkanDriver(const VulkanDriver&) = delete;
  VulkanDriver& operator=(const VulkanDriver&) = delete;

  DeviceInfo info() const override { return platform_->info; }

  std::unique_ptr<DriverObject> createBuffer(const BufferDesc& desc, const void* data) override {
    auto r = std::make_unique<BufferRes>();
    r->desc = desc;
    r->size = std::max<VkDeviceSize>(4, (desc.bytes + 3) / 4 * 4);
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = r->size;
    // Both uniform and storage usage: GL buffers are untyped, so are these.
    ci.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vkCreateBuffer(device_, &ci, nullptr, &r->buffer), "vkCreateBuffer");
    try {
      VkMemoryRequirements req;
      vkGetBufferMemoryRequirements(device_, r->buffer, &req);
      r->memory = allocate(req, false, "buffer " + desc.name);
      check(vkBindBufferMemory(device_, r->buffer, r->memory, 0), "vkBindBufferMemory");
      // Defined contents (zero) unless data is given, as on GL.
      HostBuffer staging;
      if (data != nullptr) {
        staging = createHostBuffer(desc.bytes);
        std::memcpy(staging.mapped, data, desc.bytes);
      }
      immediate([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, r->buffer, 0, VK_WHOLE_SIZE, 0);
        if (staging.buffer != VK_NULL_HANDLE) {
          fullBarrier(cmd);
          VkBufferCopy region{0, 0, desc.bytes};
          vkCmdCopyBuffer(cmd, staging.buffer, r->buffer, 1, &region);
        }
      });
      destroyHostBuffer(staging);
    } catch (...) {
      destroyBufferRes(*r);
      throw;
    }
    return r;
  }

  void updateBuffer(DriverObject& object, const BufferDesc&, const void* data, std::size_t bytes,
                    std::size_t offset) override {
    auto& r = static_cast<BufferRes&>(object);
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

  void fillBuffer(DriverObject& object, const BufferDesc&, uint32_t value) override {
    auto& r = static_cast<BufferRes&>(object);
    if (!inFrame_) {
      immediate(
          [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, r.buffer, 0, VK_WHOLE_SIZE, value); });
      return;
    }
    fullBarrier(frameCmd_);
    vkCmdFillBuffer(frameCmd_, r.buffer, 0, VK_WHOLE_SIZE, value);
  }

  std::unique_ptr<DriverObject> createTexture(const TextureDesc& desc) override {
    auto owned = std::make_unique<TextureRes>();
    TextureRes& t = *owned;
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
      throw DeviceError(
          std::string("createTexture('") + desc.name + "'): format " + formatName(desc.format) +
          " cannot be a render target, sampled and copied on " + platform_->info.device);
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
    ci.arrayLayers = desc.layers;
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
      if (desc.layers == 1) t.view = makeView(t, VK_IMAGE_VIEW_TYPE_2D, 0, 1);
      t.arrayView = makeView(t, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, desc.layers);
      t.layerViews.assign(desc.layers > 1 ? desc.layers : 0, VK_NULL_HANDLE);
      // Defined initial contents: colour 0, depth 1 (far). A fresh resource, so an
      // immediate submission is ordered correctly even inside a frame.
      immediate([&](VkCommandBuffer cmd) {
        std::vector<VkImageMemoryBarrier> barriers;
        transition(barriers, t, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        fullBarrier(cmd, barriers);
        VkImageSubresourceRange range{t.aspect, 0, 1, 0, desc.layers};
        if (depth) {
          VkClearDepthStencilValue v{1.0f, 0};
          vkCmdClearDepthStencilImage(cmd, t.image, t.layout, &v, 1, &range);
        } else {
          VkClearColorValue v{};
          vkCmdClearColorImage(cmd, t.image, t.layout, &v, 1, &range);
        }
      });
    } catch (...) {
      destroyTextureRes(t);
      throw;
    }
    return owned;
  }

  std::unique_ptr<DriverObject> createPipeline(const PipelineDesc& desc) override {
    const bool compute = desc.compute != nullptr;
    // Compile first: errors throw before any Vulkan object exists.
    std::vector<uint32_t> csSpv, vsSpv, fsSpv;
    if (compute) {
      csSpv = compileVulkanSpirv(*desc.compute, ShaderStage::Compute, desc.technique);
    } else {
      vsSpv = compileVulkanSpirv(*desc.vertex, ShaderStage::Vertex, desc.technique);
      fsSpv = compileVulkanSpirv(*desc.fragment, ShaderStage::Fragment, desc.technique);
    }

    auto owned = std::make_unique<PipelineRes>();
    PipelineRes& p = *owned;
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
        p.pipeline = createGraphicsPipeline(*platform_, desc, p.layout, makeModule(vsSpv),
                                            makeModule(fsSpv));
      }
      destroyModules();
    } catch (...) {
      destroyModules();
      destroyPipelineRes(p);
      throw;
    }
    return owned;
  }

  void release(std::unique_ptr<DriverObject> object) override {
    if (inFrame_) {
      dead_.push_back(std::move(object));  // recorded work may still use it
    } else {
      destroyObject(*object);
    }
  }

  void beginFrame() override {
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

  void beginPass(const DriverPass& pd) override {
    auto tex = [](const DriverTexture& t) -> TextureRes& {
      return static_cast<TextureRes&>(*t.object);
    };
    if (cpuTiming_) flushFrame();
    std::vector<VkImageMemoryBarrier> barriers;
    for (const DriverColorTarget& a : pd.color)
      transition(barriers, tex(a.texture), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    if (pd.depth.object)
      transition(barriers, tex(pd.depth), VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    for (const DriverTexture& s : pd.sampled)
      transition(barriers, tex(s), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    fullBarrier(frameCmd_, barriers);
    beginTiming(pd.name);

    std::vector<VkRenderingAttachmentInfo> colors;
    for (const DriverColorTarget& a : pd.color) {
      const TextureRes& t = tex(a.texture);
      VkRenderingAttachmentInfo ai{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
      ai.imageView = attachmentView(tex(a.texture), a.layer);
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
    if (pd.depth.object) {
      depthInfo.imageView = tex(pd.depth).view;
      depthInfo.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
      depthInfo.loadOp =
          pd.depthLoad == LoadOp::Clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
      depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      depthInfo.clearValue.depthStencil = {pd.depthClear, 0};
    }
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {pd.width, pd.height}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = static_cast<uint32_t>(colors.size());
    ri.pColorAttachments = colors.data();
    ri.pDepthAttachment = pd.depth.object ? &depthInfo : nullptr;
    vkCmdBeginRendering(frameCmd_, &ri);
    // Positive height: NDC y=-1 maps to framebuffer row 0 (no flip), as in GL
    // with glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE).
    VkViewport vp{0, 0, static_cast<float>(pd.width), static_cast<float>(pd.height), 0, 1};
    VkRect2D sc{{0, 0}, {pd.width, pd.height}};
    vkCmdSetViewport(frameCmd_, 0, 1, &vp);
    vkCmdSetScissor(frameCmd_, 0, 1, &sc);
    boundPipeline_ = VK_NULL_HANDLE;
  }

  void draw(DriverObject& pipeline, const PipelineDesc&, const std::vector<DriverBinding>& bindings,
            uint32_t vertexCount, uint32_t instanceCount) override {
    auto& p = static_cast<PipelineRes&>(pipeline);
    VkDescriptorSet set = makeSet(p, bindings);
    if (boundPipeline_ != p.pipeline) {
      vkCmdBindPipeline(frameCmd_, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipeline);
      boundPipeline_ = p.pipeline;
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
    vkCmdEndRendering(frameCmd_);
    endTiming();
  }

  void dispatch(const std::string& passName, DriverObject& pipeline, const PipelineDesc&,
                const std::vector<DriverBinding>& bindings, uint32_t x, uint32_t y,
                uint32_t z) override {
    auto& p = static_cast<PipelineRes&>(pipeline);
    if (cpuTiming_) flushFrame();
    std::vector<VkImageMemoryBarrier> barriers;
    for (const DriverBinding& b : bindings) {
      if (b.kind == BindingKind::SampledTexture || b.kind == BindingKind::SampledTextureArray) {
        transition(barriers, static_cast<TextureRes&>(*b.object),
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
      }
    }
    VkDescriptorSet set = makeSet(p, bindings);
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
    inFrame_ = false;  // whatever happens below, the frame is over
    struct FrameCleanup {
      VulkanDriver* d;
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

  std::vector<uint8_t> readTexture(DriverObject& object, const TextureDesc& desc) override {
    auto& t = static_cast<TextureRes&>(object);
    // Layers are copied one after the other, each tightly packed.
    const std::size_t bytes =
        std::size_t{desc.width} * desc.height * desc.layers * bytesPerPixel(desc.format);
    HostBuffer staging = createHostBuffer(bytes);
    std::vector<uint8_t> out(bytes);
    try {
      immediate([&](VkCommandBuffer cmd) {
        std::vector<VkImageMemoryBarrier> barriers;
        transition(barriers, t, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        fullBarrier(cmd, barriers);
        VkBufferImageCopy region{};
        region.imageSubresource = {t.aspect, 0, 0, desc.layers};
        region.imageExtent = {desc.width, desc.height, 1};
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

  std::vector<uint8_t> readBuffer(DriverObject& object, const BufferDesc& desc) override {
    auto& r = static_cast<BufferRes&>(object);
    std::vector<uint8_t> out(desc.bytes);
    HostBuffer staging = createHostBuffer(desc.bytes);
    try {
      immediate([&](VkCommandBuffer cmd) {
        fullBarrier(cmd);
        VkBufferCopy region{0, 0, desc.bytes};
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

 private:
  void createCommandObjects(uint32_t queueFamily) {
    VkCommandPoolCreateInfo cp{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    cp.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    cp.queueFamilyIndex = queueFamily;
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

  // The objects of the driver itself; resources came back through release().
  void cleanup() {
    if (device_ == VK_NULL_HANDLE) return;
    vkDeviceWaitIdle(device_);
    finishFrameResources();
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
    fence_ = VK_NULL_HANDLE;
    cmdPool_ = VK_NULL_HANDLE;
  }

  void destroyObject(DriverObject& object) {
    if (auto* b = dynamic_cast<BufferRes*>(&object)) destroyBufferRes(*b);
    if (auto* t = dynamic_cast<TextureRes*>(&object)) destroyTextureRes(*t);
    if (auto* p = dynamic_cast<PipelineRes*>(&object)) destroyPipelineRes(*p);
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
    for (VkImageView v : t.layerViews)
      if (v != VK_NULL_HANDLE) vkDestroyImageView(device_, v, nullptr);
    t.layerViews.clear();
    if (t.arrayView != VK_NULL_HANDLE) vkDestroyImageView(device_, t.arrayView, nullptr);
    t.arrayView = VK_NULL_HANDLE;
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
    for (auto& object : dead_) destroyObject(*object);
    dead_.clear();
    for (VkDescriptorPool p : descPools_) vkResetDescriptorPool(device_, p, 0);
    descPool_ = 0;
  }
  VkImageView makeView(const TextureRes& t, VkImageViewType type, uint32_t first, uint32_t count) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = t.image;
    vi.viewType = type;
    vi.format = t.format;
    vi.subresourceRange = {t.aspect, 0, 1, first, count};
    VkImageView v = VK_NULL_HANDLE;
    check(vkCreateImageView(device_, &vi, nullptr, &v), "vkCreateImageView");
    return v;
  }

  // The view a pass renders into: the texture's own, or its layer's (made once).
  VkImageView attachmentView(TextureRes& t, uint32_t layer) {
    if (t.layerViews.empty()) return t.view;
    VkImageView& v = t.layerViews[layer];
    if (v == VK_NULL_HANDLE) v = makeView(t, VK_IMAGE_VIEW_TYPE_2D, layer, 1);
    return v;
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
    b.subresourceRange = {t.aspect, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
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

  // A fresh descriptor set for the bindings, which the front end has checked
  // and ordered as the pipeline declares them.
  VkDescriptorSet makeSet(const PipelineRes& p, const std::vector<DriverBinding>& bindings) {
    if (bindings.empty()) return VK_NULL_HANDLE;
    std::vector<VkDescriptorBufferInfo> bufInfos;
    std::vector<VkDescriptorImageInfo> imgInfos;
    bufInfos.reserve(bindings.size());
    imgInfos.reserve(bindings.size());
    std::vector<VkWriteDescriptorSet> writes;
    for (const DriverBinding& b : bindings) {
      VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w.dstBinding = b.binding;
      w.descriptorCount = 1;
      w.descriptorType = toVk(b.kind);
      if (b.kind == BindingKind::SampledTexture || b.kind == BindingKind::SampledTextureArray) {
        const auto& t = static_cast<const TextureRes&>(*b.object);
        const VkImageView v = b.kind == BindingKind::SampledTexture ? t.view : t.arrayView;
        imgInfos.push_back(
            {samplers_[t.linear ? 1 : 0], v, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
        w.pImageInfo = &imgInfos.back();
      } else {
        const auto& r = static_cast<const BufferRes&>(*b.object);
        const VkDeviceSize limit = b.kind == BindingKind::UniformBuffer
                                       ? limits_.maxUniformBufferRange
                                       : limits_.maxStorageBufferRange;
        bufInfos.push_back({r.buffer, 0, std::min<VkDeviceSize>(r.size, limit)});
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
  std::unique_ptr<VulkanPlatform> platform_;
  // Copied from the platform, which outlives every use.
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkPhysicalDeviceLimits limits_{};
  VkPhysicalDeviceMemoryProperties memProps_{};
  float timestampPeriod_ = 1.0f;
  uint32_t timestampBits_ = 0;
  bool cpuTiming_ = false;

  VkCommandPool cmdPool_ = VK_NULL_HANDLE;
  VkCommandBuffer frameCmd_ = VK_NULL_HANDLE;
  VkCommandBuffer immCmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSampler samplers_[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};  // nearest, linear

  bool inFrame_ = false;
  VkPipeline boundPipeline_ = VK_NULL_HANDLE;  // in the open pass
  std::vector<HostBuffer> frameStaging_;
  std::vector<std::unique_ptr<DriverObject>> dead_;  // released during the frame
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

std::unique_ptr<Driver> createVulkanDriver(const DeviceOptions& opts) {
  return std::make_unique<VulkanDriver>(std::make_unique<VulkanPlatform>(opts.validation));
}

}  // namespace sb
