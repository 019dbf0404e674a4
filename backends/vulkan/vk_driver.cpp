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
//
// This file holds the driver class: frames, passes, draws, dispatches,
// descriptor sets and timing. The objects it records with (buffers, textures,
// pipelines), memory, staging, the immediate submission and the barriers are in
// vk_resources.h/.cpp; graphics pipeline state is in vk_pipeline.cpp.
#include "backends/vulkan/vk_driver.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "backends/vulkan/vk_pipeline.h"
#include "backends/vulkan/vk_platform.h"
#include "backends/vulkan/vk_resources.h"
#include "backends/vulkan/vk_shader.h"
#include "backends/vulkan/vk_util.h"
#include "backends/vulkan/vk_window.h"
#include "backends/window/glfw_window.h"

namespace sb {

namespace {

constexpr uint32_t kQueriesPerPool = 128;  // even: a pass's pair never straddles pools
constexpr VkDeviceSize kMaxCmdUpdateBytes = 65536;

// Every layer of a texture, tightly packed one after the other (read and write back).
VkBufferImageCopy allLayers(const TextureRes& t, const TextureDesc& desc) {
  VkBufferImageCopy region{};
  region.imageSubresource = {t.aspect, 0, 0, desc.layers};
  region.imageExtent = {desc.width, desc.height, 1};
  return region;
}

class VulkanDriver final : public Driver {
 public:
  explicit VulkanDriver(std::unique_ptr<VulkanPlatform> platform)
      : platform_(std::move(platform)), resources_(*platform_) {
    const VulkanPlatform& p = *platform_;
    device_ = p.device;
    limits_ = p.limits;
    timestampPeriod_ = p.timestampPeriod;
    timestampBits_ = p.timestampBits;
    cpuTiming_ = p.cpuTiming;
    statistics_ = p.statistics;
    preciseOcclusion_ = p.preciseOcclusion;
    uniformsAsStorage_ = p.uniformsAsStorage;
    try {
      createCommandObjects();
      if (platform_->surface != VK_NULL_HANDLE) {
        swapchain_ = std::make_unique<VulkanSwapchain>(*platform_, resources_);
        platform_->info.present = swapchain_->mode();
      }
    } catch (...) {
      swapchain_.reset();
      cleanup();
      throw;
    }
  }
  ~VulkanDriver() override { cleanup(); }
  VulkanDriver(const VulkanDriver&) = delete;
  VulkanDriver& operator=(const VulkanDriver&) = delete;

  DeviceInfo info() const override { return platform_->info; }

  MemoryBudget memoryBudget() const override {
    // The largest device-local heap: what VK_EXT_memory_budget says is left
    // of it, else its size. A CPU device's heaps are host memory, which the
    // host's own figure (free memory, address-space limit) bounds more tightly.
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    VkPhysicalDeviceMemoryProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2,
                                            platform_->memoryBudget ? &budget : nullptr};
    vkGetPhysicalDeviceMemoryProperties2(platform_->physical, &props);
    MemoryBudget best;
    const VkPhysicalDeviceMemoryProperties& m = props.memoryProperties;
    for (uint32_t i = 0; i < m.memoryHeapCount; ++i) {
      if (!(m.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)) continue;
      MemoryBudget heap{m.memoryHeaps[i].size, "Vulkan heap size"};
      if (platform_->memoryBudget) {
        const VkDeviceSize left = budget.heapBudget[i] > budget.heapUsage[i]
                                      ? budget.heapBudget[i] - budget.heapUsage[i]
                                      : 0;
        heap = {left, "VK_EXT_memory_budget"};
      }
      if (heap.bytes > best.bytes) best = heap;
    }
    if (platform_->cpuDevice) {
      const MemoryBudget host = hostMemoryBudget();
      if (host.bytes && (!best.bytes || host.bytes < best.bytes)) best = host;
    }
    return best;
  }

  std::unique_ptr<DriverObject> createBuffer(const BufferDesc& desc, const void* data) override {
    return resources_.createBuffer(desc, data);
  }

  void updateBuffer(DriverObject& object, const BufferDesc&, const void* data, std::size_t bytes,
                    std::size_t offset) override {
    auto& r = static_cast<BufferRes&>(object);
    if (!inFrame_) {
      resources_.upload(data, bytes, [&](VkCommandBuffer cmd, VkBuffer staging) {
        VkBufferCopy region{0, offset, bytes};
        vkCmdCopyBuffer(cmd, staging, r.buffer, 1, &region);
      });
      return;
    }
    // Inside a frame: ordered with the recorded work. The barrier orders this
    // write after earlier reads; the next pass's barrier orders later reads.
    fullBarrier(frameCmd_);
    if (bytes <= kMaxCmdUpdateBytes && bytes % 4 == 0 && offset % 4 == 0) {
      vkCmdUpdateBuffer(frameCmd_, r.buffer, offset, bytes, data);
    } else {
      HostBuffer staging = resources_.createHostBuffer(bytes);
      frameStaging_.push_back(staging);
      std::memcpy(staging.mapped, data, bytes);
      VkBufferCopy region{0, offset, bytes};
      vkCmdCopyBuffer(frameCmd_, staging.buffer, r.buffer, 1, &region);
    }
  }

  void fillBuffer(DriverObject& object, const BufferDesc&, uint32_t value) override {
    auto& r = static_cast<BufferRes&>(object);
    if (!inFrame_) {
      resources_.immediate(
          [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, r.buffer, 0, VK_WHOLE_SIZE, value); });
      return;
    }
    fullBarrier(frameCmd_);
    vkCmdFillBuffer(frameCmd_, r.buffer, 0, VK_WHOLE_SIZE, value);
  }

  std::unique_ptr<DriverObject> createTexture(const TextureDesc& desc) override {
    return resources_.createTexture(desc);
  }

  std::size_t accelerationStructureBytes(uint32_t boxes) const override {
    return resources_.accelerationStructureBytes(boxes);
  }

  // Built by its own submission, also inside a frame (a build cannot be
  // recorded inside a rendering): the boxes are those already on the device.
  std::unique_ptr<DriverObject> createAccelerationStructure(const BufferDesc& desc,
                                                            DriverObject& aabbs,
                                                            uint32_t boxes) override {
    return resources_.createAccelerationStructure(desc, static_cast<BufferRes&>(aabbs), boxes);
  }

  std::unique_ptr<DriverObject> createPipeline(const PipelineDesc& desc) override {
    const bool compute = desc.compute != nullptr;
    // Compile first: errors throw before any Vulkan object exists.
    std::vector<uint32_t> csSpv, vsSpv, fsSpv;
    if (compute) {
      csSpv = compileVulkanSpirv(*desc.compute, ShaderStage::Compute, desc.technique,
                                 uniformsAsStorage_);
    } else {
      const bool mesh = desc.vertex->meshGroupVertices > 0;
      vsSpv = compileVulkanSpirv(*desc.vertex, mesh ? ShaderStage::Mesh : ShaderStage::Vertex,
                                 desc.technique, uniformsAsStorage_);
      fsSpv = compileVulkanSpirv(*desc.fragment, ShaderStage::Fragment, desc.technique,
                                 uniformsAsStorage_);
    }

    auto owned = std::make_unique<PipelineRes>();
    PipelineRes& p = *owned;
    for (const auto* spv : {&csSpv, &vsSpv, &fsSpv}) {
      const std::set<uint32_t> storage = storageBufferBindings(*spv);
      for (const BindingSlot& s : desc.bindings) {
        if (s.kind == BindingKind::UniformBuffer && storage.count(s.binding) != 0)
          p.uniformsAsStorage.insert(s.binding);
      }
    }
    std::vector<VkShaderModule> modules;
    auto destroyModules = [&] {
      for (VkShaderModule m : modules) vkDestroyShaderModule(device_, m, nullptr);
      modules.clear();
    };
    try {
      std::vector<VkDescriptorSetLayoutBinding> lb;
      for (const BindingSlot& s : desc.bindings) {
        lb.push_back(
            {s.binding, descriptorType(p, s.binding, s.kind), 1, VK_SHADER_STAGE_ALL, nullptr});
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
        p.meshGroupVertices = desc.vertex->meshGroupVertices;
        p.pipeline = createGraphicsPipeline(*platform_, desc, p.layout, makeModule(vsSpv),
                                            makeModule(fsSpv));
      }
      destroyModules();
    } catch (...) {
      destroyModules();
      resources_.destroyPipeline(p);
      throw;
    }
    return owned;
  }

  void release(std::unique_ptr<DriverObject> object) override {
    if (inFrame_) {
      dead_.push_back(std::move(object));  // recorded work may still use it
    } else {
      pipelinesDestroyed_ = pipelinesDestroyed_ || dynamic_cast<PipelineRes*>(object.get());
      resources_.destroyObject(*object);
    }
  }

  void finishReleases() override {
    if (inFrame_ || !pipelinesDestroyed_ || !platform_->cpuDevice) return;
    pipelinesDestroyed_ = false;
    // lavapipe frees a destroyed pipeline (its shaders' JIT code and NIR) only
    // at the end of its next submission, on its submit thread, after the
    // fence is signalled; a second submission, processed in order, waits for
    // that. Without them the trim after a group missed a renderer's pipelines
    // (the view session's resident memory 24 MiB above what it held).
    resources_.immediate([](VkCommandBuffer) {});
    resources_.immediate([](VkCommandBuffer) {});
  }

  void beginFrame() override {
    resetAndBegin(frameCmd_);
    inFrame_ = true;
    passNames_.clear();
    passQueries_.clear();
    cpuMs_.clear();
    cpuStartMs_.clear();
    frameStart_ = std::chrono::steady_clock::now();
    timings_.clear();
    queryCount_ = 0;
    queryPoolsReset_ = 0;
    counted_.clear();
    for (VkQueryPool q : counterPools_) vkResetQueryPool(device_, q, 0, kQueriesPerPool);
  }

  void beginPass(const DriverPass& pd) override {
    auto tex = [](const DriverTexture& t) -> TextureRes& {
      return static_cast<TextureRes&>(*t.object);
    };
    if (cpuTiming_) flushFrame();
    std::vector<VkImageMemoryBarrier> barriers;
    for (const DriverColorTarget& a : pd.color) {
      transition(barriers, tex(a.texture), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
      if (a.resolve.object)
        transition(barriers, tex(a.resolve), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    }
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
      ai.imageView = resources_.attachmentView(tex(a.texture), a.layer);
      ai.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      ai.loadOp =
          a.load == LoadOp::Clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
      ai.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      if (a.resolve.object) {  // averaged into the single-sampled target at the end
        ai.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        ai.resolveImageView = tex(a.resolve).view;
        ai.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      }
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
    beginCounting(true);
  }

  void draw(DriverObject& pipeline, const PipelineDesc& desc,
            const std::vector<DriverBinding>& bindings, uint32_t vertexCount,
            uint32_t instanceCount) override {
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
    if (vertexCount == 0 || instanceCount == 0) return;
    if (p.meshGroupVertices == 0) {
      vkCmdDraw(frameCmd_, vertexCount, instanceCount, 0, 0);
      return;
    }
    // The vertex path's vertices in groups of meshGroupVertices, in rows of at most
    // maxMeshGroupsX (ShaderCode::meshGroupVertices).
    const uint64_t groups = (uint64_t{vertexCount} + p.meshGroupVertices - 1) / p.meshGroupVertices;
    const uint64_t x = std::min<uint64_t>(groups, platform_->maxMeshGroupsX);
    const uint64_t y = (groups + x - 1) / x;
    if (x * y > platform_->maxMeshGroupsTotal)
      throw DeviceError("draw('" + desc.name + "'): " + std::to_string(groups) +
                        " mesh workgroups, over the device's " +
                        std::to_string(platform_->maxMeshGroupsTotal) + " per draw");
    platform_->drawMeshTasks(frameCmd_, static_cast<uint32_t>(x), static_cast<uint32_t>(y), 1);
  }

  void endPass() override {
    endCounting();  // inside the rendering, as begun: the resolves are not counted
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
    beginCounting(false);
    if (x > 0 && y > 0 && z > 0) vkCmdDispatch(frameCmd_, x, y, z);
    endCounting();
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
    resources_.submitAndWait(frameCmd_);

    timings_.clear();
    if (cpuTiming_) {
      for (std::size_t i = 0; i < passNames_.size(); ++i) {
        timings_.push_back({passNames_[i], i < cpuMs_.size() ? cpuMs_[i] : 0.0,
                            i < cpuStartMs_.size() ? cpuStartMs_[i] : 0.0});
      }
      readCounts();
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
      const uint64_t since = (stamps[q] - stamps[passQueries_.front()]) & mask;
      timings_.push_back({passNames_[i], static_cast<double>(ticks) * timestampPeriod_ / 1e6,
                          static_cast<double>(since) * timestampPeriod_ / 1e6});
    }
    readCounts();
  }

  std::vector<PassTiming> lastFrameTimings() const override { return timings_; }

  std::vector<uint8_t> readTexture(DriverObject& object, const TextureDesc& desc) override {
    auto& t = static_cast<TextureRes&>(object);
    // Layers are copied one after the other, each tightly packed.
    const std::size_t bytes =
        std::size_t{desc.width} * desc.height * desc.layers * bytesPerPixel(desc.format);
    return resources_.download(bytes, [&](VkCommandBuffer cmd, VkBuffer staging) {
      std::vector<VkImageMemoryBarrier> barriers;
      transition(barriers, t, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
      fullBarrier(cmd, barriers);
      const VkBufferImageCopy region = allLayers(t, desc);
      vkCmdCopyImageToBuffer(cmd, t.image, t.layout, staging, 1, &region);
    });
  }

  std::vector<uint8_t> readBuffer(DriverObject& object, const BufferDesc& desc) override {
    auto& r = static_cast<BufferRes&>(object);
    return resources_.download(desc.bytes, [&](VkCommandBuffer cmd, VkBuffer staging) {
      fullBarrier(cmd);
      VkBufferCopy region{0, 0, desc.bytes};
      vkCmdCopyBuffer(cmd, r.buffer, staging, 1, &region);
    });
  }

  void writeTexture(DriverObject& object, const TextureDesc& desc,
                    const std::vector<uint8_t>& bytes) override {
    auto& t = static_cast<TextureRes&>(object);
    resources_.upload(bytes.data(), bytes.size(), [&](VkCommandBuffer cmd, VkBuffer staging) {
      std::vector<VkImageMemoryBarrier> barriers;
      transition(barriers, t, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
      fullBarrier(cmd, barriers);
      const VkBufferImageCopy region = allLayers(t, desc);
      vkCmdCopyBufferToImage(cmd, staging, t.image, t.layout, 1, &region);
      fullBarrier(cmd);
    });
  }

  Window* window() override { return platform_->window.get(); }

  bool present(DriverObject& t, const TextureDesc&, PresentedImage* capture) override {
    return swapchain_->present(static_cast<TextureRes&>(t), capture);
  }

 private:
  void createCommandObjects() {
    frameCmd_ = resources_.allocateCommandBuffer();

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
  // The command pool and fence go with resources_, after this.
  void cleanup() {
    if (device_ == VK_NULL_HANDLE) return;
    vkDeviceWaitIdle(device_);
    finishFrameResources();
    for (VkDescriptorPool p : descPools_) vkDestroyDescriptorPool(device_, p, nullptr);
    descPools_.clear();
    for (VkQueryPool q : queryPools_) vkDestroyQueryPool(device_, q, nullptr);
    queryPools_.clear();
    for (VkQueryPool q : counterPools_) vkDestroyQueryPool(device_, q, nullptr);
    counterPools_.clear();
    for (VkSampler& s : samplers_) {
      if (s != VK_NULL_HANDLE) vkDestroySampler(device_, s, nullptr);
      s = VK_NULL_HANDLE;
    }
  }

  // Frees what a frame kept alive (staging, destroyed resources) and resets the
  // descriptor pools. Called once the frame's work is complete (or abandoned).
  void finishFrameResources() {
    for (HostBuffer& h : frameStaging_) resources_.destroyHostBuffer(h);
    frameStaging_.clear();
    for (auto& object : dead_) resources_.destroyObject(*object);
    dead_.clear();
    for (VkDescriptorPool p : descPools_) vkResetDescriptorPool(device_, p, 0);
    descPool_ = 0;
  }

  // CPU-timing mode: submit what is recorded so far, wait, and go on recording.
  void flushFrame() {
    check(vkEndCommandBuffer(frameCmd_), "vkEndCommandBuffer");
    resources_.submitAndWait(frameCmd_);
    resetAndBegin(frameCmd_);
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
      cpuStartMs_.push_back(std::chrono::duration<double, std::milli>(t0 - frameStart_).count());
      return;
    }
    const uint32_t q = passQueries_.back() + 1;
    vkCmdWriteTimestamp(frameCmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                        queryPools_[q / kQueriesPerPool], q % kQueriesPerPool);
  }

  // The work counters: a pipeline statistics query and (render passes) an
  // occlusion query per pass, from pools of kQueriesPerPool of each kind
  // (statistics pool, occlusion pool alternate in counterPools_), reset from
  // the host before the frame or when made.
  static constexpr VkQueryPipelineStatisticFlags kStatistics =
      VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_VERTICES_BIT |
      VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT |
      VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT |
      VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT |
      VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT |
      VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT |
      VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT;
  static constexpr uint32_t kStatisticValues = 7;  // the bits above, in bit order

  VkQueryPool counterPool(uint32_t pass, bool occlusion) {
    const std::size_t index = 2 * (pass / kQueriesPerPool) + (occlusion ? 1 : 0);
    while (counterPools_.size() <= index) {
      const bool makeOcclusion = counterPools_.size() % 2 == 1;
      VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      qi.queryType = makeOcclusion ? VK_QUERY_TYPE_OCCLUSION : VK_QUERY_TYPE_PIPELINE_STATISTICS;
      qi.pipelineStatistics = makeOcclusion ? 0 : kStatistics;
      qi.queryCount = kQueriesPerPool;
      VkQueryPool qp = VK_NULL_HANDLE;
      check(vkCreateQueryPool(device_, &qi, nullptr, &qp), "vkCreateQueryPool");
      vkResetQueryPool(device_, qp, 0, kQueriesPerPool);
      counterPools_.push_back(qp);
    }
    return counterPools_[index];
  }
  void beginCounting(bool graphics) {
    if (!statistics_) return;
    const uint32_t pass = static_cast<uint32_t>(counted_.size());
    counted_.push_back(graphics);
    vkCmdBeginQuery(frameCmd_, counterPool(pass, false), pass % kQueriesPerPool, 0);
    if (graphics)
      vkCmdBeginQuery(frameCmd_, counterPool(pass, true), pass % kQueriesPerPool,
                      preciseOcclusion_ ? VK_QUERY_CONTROL_PRECISE_BIT : 0);
  }
  void endCounting() {
    if (!statistics_) return;
    const uint32_t pass = static_cast<uint32_t>(counted_.size() - 1);
    vkCmdEndQuery(frameCmd_, counterPool(pass, false), pass % kQueriesPerPool);
    if (counted_.back()) vkCmdEndQuery(frameCmd_, counterPool(pass, true), pass % kQueriesPerPool);
  }
  // After the frame's wait: each pass's counts into its timing.
  void readCounts() {
    for (uint32_t p = 0; p < counted_.size() && p < timings_.size(); ++p) {
      ApiCounts v{};  // the statistics (kStatisticValues), then the occlusion query
      check(vkGetQueryPoolResults(device_, counterPool(p, false), p % kQueriesPerPool, 1,
                                  kStatisticValues * sizeof(uint64_t), v.data(),
                                  kStatisticValues * sizeof(uint64_t),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults (statistics)");
      if (counted_[p])
        check(vkGetQueryPoolResults(device_, counterPool(p, true), p % kQueriesPerPool, 1,
                                    sizeof(uint64_t), &v[kStatisticValues], sizeof(uint64_t),
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "vkGetQueryPoolResults (occlusion)");
      setApiCounts(timings_[p].work, v);
    }
  }

  VkDescriptorSet allocateSet(VkDescriptorSetLayout layout) {
    for (;;) {
      if (descPool_ == descPools_.size()) {
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1024},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3072},
                                              {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1024},
                                              {VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 512}};
        VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pi.maxSets = 512;
        // Acceleration structures only where the device has them (an invalid type elsewhere).
        pi.poolSizeCount = platform_->info.rayQuery ? 4 : 3;
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

  // A binding's descriptor type: a uniform block the shaders read as a storage
  // buffer (VulkanPlatform::uniformsAsStorage) takes a storage buffer.
  static VkDescriptorType descriptorType(const PipelineRes& p, uint32_t binding, BindingKind kind) {
    return kind == BindingKind::UniformBuffer && p.uniformsAsStorage.count(binding) != 0
               ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
               : toVk(kind);
  }

  // A fresh descriptor set for the bindings, which the front end has checked
  // and ordered as the pipeline declares them.
  VkDescriptorSet makeSet(const PipelineRes& p, const std::vector<DriverBinding>& bindings) {
    if (bindings.empty()) return VK_NULL_HANDLE;
    std::vector<VkDescriptorBufferInfo> bufInfos;
    std::vector<VkDescriptorImageInfo> imgInfos;
    std::vector<VkWriteDescriptorSetAccelerationStructureKHR> accelInfos;
    bufInfos.reserve(bindings.size());
    imgInfos.reserve(bindings.size());
    accelInfos.reserve(bindings.size());
    std::vector<VkWriteDescriptorSet> writes;
    for (const DriverBinding& b : bindings) {
      VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w.dstBinding = b.binding;
      w.descriptorCount = 1;
      w.descriptorType = descriptorType(p, b.binding, b.kind);
      if (b.kind == BindingKind::SampledTexture || b.kind == BindingKind::SampledTextureArray) {
        const auto& t = static_cast<const TextureRes&>(*b.object);
        const VkImageView v = b.kind == BindingKind::SampledTexture ? t.view : t.arrayView;
        imgInfos.push_back(
            {samplers_[t.linear ? 1 : 0], v, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
        w.pImageInfo = &imgInfos.back();
      } else if (b.kind == BindingKind::AccelerationStructure) {
        const auto& a = static_cast<const AccelerationStructureRes&>(*b.object);
        accelInfos.push_back({VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR,
                              nullptr, 1, &a.top});
        w.pNext = &accelInfos.back();
      } else {
        const auto& r = static_cast<const BufferRes&>(*b.object);
        const VkDeviceSize limit = w.descriptorType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                       ? limits_.maxUniformBufferRange
                                       : limits_.maxStorageBufferRange;
        // A uniform block reads only its declared size; a storage buffer over the
        // limit would be bound in part, so it is refused (Device::createBuffer
        // refuses it sooner, when it is made as storage).
        if (w.descriptorType != VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER && r.size > limit)
          throw DeviceError("Vulkan: buffer '" + r.desc.name + "' (" + std::to_string(r.size) +
                            " bytes) bound as storage: more than maxStorageBufferRange (" +
                            std::to_string(limit) + " bytes)");
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
  VulkanResources resources_;                   // after platform_: destroyed before it
  std::unique_ptr<VulkanSwapchain> swapchain_;  // window platform; destroyed before resources_
  // Copied from the platform, which outlives every use.
  VkDevice device_ = VK_NULL_HANDLE;
  VkPhysicalDeviceLimits limits_{};
  float timestampPeriod_ = 1.0f;
  uint32_t timestampBits_ = 0;
  bool cpuTiming_ = false;

  VkCommandBuffer frameCmd_ = VK_NULL_HANDLE;                 // from resources_' pool
  VkSampler samplers_[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};  // nearest, linear

  bool inFrame_ = false;
  VkPipeline boundPipeline_ = VK_NULL_HANDLE;  // in the open pass
  std::vector<HostBuffer> frameStaging_;
  std::vector<std::unique_ptr<DriverObject>> dead_;  // released during the frame
  std::vector<VkDescriptorPool> descPools_;
  std::size_t descPool_ = 0;  // first pool that may still have room this frame
  std::vector<VkQueryPool> queryPools_;
  bool statistics_ = false, preciseOcclusion_ = false;
  bool uniformsAsStorage_ = false;
  bool pipelinesDestroyed_ = false;        // since the last finishReleases()
  std::vector<VkQueryPool> counterPools_;  // statistics, occlusion, statistics, ...
  std::vector<bool> counted_;              // this frame's passes: render pass or compute
  uint32_t queryCount_ = 0;
  uint32_t queryPoolsReset_ = 0;
  std::vector<std::string> passNames_;
  std::vector<uint32_t> passQueries_;
  std::vector<double> cpuMs_;
  std::vector<double> cpuStartMs_;  // from frameStart_
  std::chrono::steady_clock::time_point frameStart_;
  std::vector<PassTiming> timings_;
};

}  // namespace

std::unique_ptr<Driver> createVulkanDriver(const DeviceOptions& opts) {
  if (opts.platform == "window") {
    const VulkanWindowRequest window{opts.windowWidth, opts.windowHeight, opts.windowTitle};
    return std::make_unique<VulkanDriver>(
        std::make_unique<VulkanPlatform>(opts.validation, &window));
  }
  return std::make_unique<VulkanDriver>(std::make_unique<VulkanPlatform>(opts.validation));
}

}  // namespace sb
