#include "backends/device.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <new>
#include <set>
#include <tuple>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "backends/device_records.h"
#include "backends/driver.h"
#include "backends/driver_env.h"

namespace sb {

namespace {
struct FormatInfo {
  const char* name;
  std::size_t bytes;
  bool depth, integer;
};
// In the order of enum class Format (device.h).
constexpr FormatInfo kFormats[] = {
    {"RGBA8", 4, false, false},    {"RGBA16F", 8, false, false}, {"RGBA32F", 16, false, false},
    {"R32F", 4, false, false},     {"RG32F", 8, false, false},   {"R32UI", 4, false, true},
    {"RGBA32UI", 16, false, true}, {"Depth32F", 4, true, false},
};
static_assert(std::size(kFormats) == static_cast<std::size_t>(Format::Depth32F) + 1);
const FormatInfo& info(Format f) { return kFormats[static_cast<std::size_t>(f)]; }
}  // namespace

std::size_t bytesPerPixel(Format f) { return info(f).bytes; }
bool isDepthFormat(Format f) { return info(f).depth; }
bool isIntegerFormat(Format f) { return info(f).integer; }
const char* formatName(Format f) { return info(f).name; }

// ---- the front end: handle tables, frame/pass state, contract checks (making
// resources and counting their memory: device_memory.cpp) ----

using device_detail::namingAllocation;
using device_detail::quoted;
using device_detail::record;
using device_detail::textureBytes;

namespace {
// Counts a resource once per pass execution: the first access kind it was
// counted with stays (an attachment loaded is "read" and written).
// Several layers of one array attached are one entry with their layers.
void touch(PassWork& w, std::set<std::tuple<char, uint32_t, uint32_t>>& seen, char kind,
           uint32_t id, uint32_t layer, PassResource r) {
  if (!seen.insert({kind, id, layer}).second) return;
  (r.access == "write"  ? w.bytesWritten
   : r.access == "read" ? w.bytesRead
                        : w.bytesStorage) += r.bytes;
  auto it = std::find_if(w.resources.begin(), w.resources.end(), [&](const PassResource& x) {
    return x.name == r.name && x.access == r.access;
  });
  if (it == w.resources.end()) {
    w.resources.push_back(std::move(r));
  } else {
    it->layers += r.layers;
    it->bytes += r.bytes;
  }
}

PassResource textureTouch(const TextureDesc& d, uint32_t layers, const char* access) {
  const uint64_t bytes =
      uint64_t{d.width} * d.height * layers * d.samples * bytesPerPixel(d.format);
  return {d.name, formatName(d.format), d.width, d.height, layers, d.samples, bytes, access};
}
}  // namespace

PassWork& PassWork::operator+=(const PassWork& o) {
  statistics = statistics || o.statistics;
  for (auto count :
       {&PassWork::vertices, &PassWork::primitives, &PassWork::vertexInvocations,
        &PassWork::clipInvocations, &PassWork::clipPrimitives, &PassWork::fragmentInvocations,
        &PassWork::computeInvocations, &PassWork::samplesPassed, &PassWork::bytesWritten,
        &PassWork::bytesRead, &PassWork::bytesStorage})
    this->*count += o.*count;
  draws += o.draws;
  dispatches += o.dispatches;
  for (const PassResource& r : o.resources) {
    auto it = std::find_if(resources.begin(), resources.end(), [&](const PassResource& x) {
      return x.name == r.name && x.access == r.access;
    });
    if (it == resources.end())
      resources.push_back(r);
    else
      it->bytes += r.bytes;
  }
  return *this;
}

namespace {
// A pass or a pipeline has at most the device's colour targets.
void checkColorCount(const std::string& where, std::size_t count, uint32_t limit) {
  if (count > limit)
    throw DeviceError(where + ": " + std::to_string(count) +
                      " colour targets; the device allows at most " + std::to_string(limit) +
                      " (Device::maxColorAttachments)");
}
}  // namespace

Device::Device(std::unique_ptr<Driver> driver) : driver_(std::move(driver)) {
  const DeviceInfo i = driver_->info();
  maxColorAttachments_ = i.maxColorAttachments;
  sampleCounts_ = i.sampleCounts | 1u;
}

bool Device::supportsSamples(uint32_t samples) const {
  // A power of two that the mask has.
  return samples != 0 && (samples & (samples - 1)) == 0 && (sampleCounts_ & samples) != 0;
}

std::string Device::sampleCountsText() const {
  std::string out;
  for (uint32_t c = 1; c != 0 && c <= sampleCounts_; c <<= 1)
    if (sampleCounts_ & c) out += (out.empty() ? "" : ", ") + std::to_string(c);
  return out;
}

Device::~Device() {
  // Native objects go back to the driver that made them, before it goes.
  auto releaseAll = [this](auto& table) {
    for (auto& [id, rec] : table)
      if (rec->object) driver_->release(std::move(rec->object));
    table.clear();
  };
  releaseAll(pipelines_);
  releaseAll(textures_);
  releaseAll(buffers_);
}

DeviceInfo Device::info() const {
  DeviceInfo i = driver_->info();
  i.driverName = currentDriver();  // the process's, set before any driver loaded
  return i;
}

namespace {
// Multisampled textures are render targets only: their samples leave them by a resolve.
void requireSingleSampled(const TextureDesc& d, const char* call) {
  if (d.samples != 1)
    throw DeviceError(quoted(call, d.name) + ": a multisampled texture (" +
                      std::to_string(d.samples) +
                      " samples); resolve it into a single-sampled one");
}
}  // namespace

Device::BufferRec& Device::buffer(Buffer b, const std::string& where) {
  return record(buffers_, b.id, "buffer", where);
}

Device::TextureRec& Device::texture(Texture t, const std::string& where) {
  return record(textures_, t.id, "texture", where);
}

const Device::TextureRec& Device::texture(Texture t, const std::string& where) const {
  return record(textures_, t.id, "texture", where);
}

const Device::BufferRec& Device::buffer(Buffer b, const std::string& where) const {
  return record(buffers_, b.id, "buffer", where);
}

Device::PipelineRec& Device::pipeline(Pipeline p, const std::string& where) {
  return record(pipelines_, p.id, "pipeline", where);
}

// Buffers of usage AccelerationStructure are built by the device, never
// written or read by calls.
void Device::requireContents(const BufferRec& r, const char* call) const {
  if (r.desc.usage == BufferUsage::AccelerationStructure)
    throw DeviceError(quoted(call, r.desc.name) +
                      ": an acceleration structure (the device builds its contents)");
}

// inFrame/inPass: what the call needs (a frame open; a pass open, or none).
void Device::requireFrame(const std::string& where, bool inFrame, bool inPass) const {
  if (inFrame && !inFrame_) throw DeviceError(where + ": outside a frame (call beginFrame first)");
  if (!inFrame && inFrame_) throw DeviceError(where + ": only outside a frame (after endFrame)");
  if (inPass && !inPass_) throw DeviceError(where + ": outside a pass (call beginPass first)");
  if (!inPass && inPass_)
    throw DeviceError(where + ": inside pass '" + pass_->name + "' (call endPass first)");
}

Buffer Device::createBuffer(const BufferDesc& given, const void* data) {
  BufferDesc desc = given;
  desc.name = labelled(given.name);
  const std::string where = quoted("createBuffer", desc.name);
  if (desc.bytes == 0) throw DeviceError(where + ": zero size");
  if (desc.usage == BufferUsage::AccelerationStructure)
    throw DeviceError(where + ": usage AccelerationStructure (use createAccelerationStructure)");
  const bool now = data && !deferMaking_;
  if (now) {
    guardMaking(desc.name, desc.owner, desc.bytes);
    checkStorageRange(desc);
  }
  // Created now only when it has contents to take (and making is not
  // deferred); otherwise when first used.
  auto rec = std::make_unique<BufferRec>(BufferRec{
      desc,
      now ? namingAllocation("making buffer '" + desc.name + "' (" + ownerName(desc.owner) + ")",
                             desc.bytes, [&] { return driver_->createBuffer(desc, data); })
          : nullptr,
      group_});
  if (data && !now) {
    const auto* bytes = static_cast<const uint8_t*>(data);
    rec->pending.assign(bytes, bytes + desc.bytes);
  }
  const uint32_t id = nextId_++;
  buffers_.emplace(id, std::move(rec));
  return Buffer{id};
}

void Device::updateBuffer(Buffer b, const void* data, std::size_t bytes, std::size_t offset) {
  BufferRec& r = buffer(b, "updateBuffer");
  requireContents(r, "updateBuffer");
  const std::string where = quoted("updateBuffer", r.desc.name);
  if (inPass_)
    throw DeviceError(where + ": inside pass '" + pass_->name +
                      "': buffers may only be updated between passes");
  if (offset > r.desc.bytes || bytes > r.desc.bytes - offset)
    throw DeviceError(where + ": " + std::to_string(bytes) + " bytes at offset " +
                      std::to_string(offset) + " exceed its " + std::to_string(r.desc.bytes) +
                      " bytes");
  if (bytes == 0) return;
  driver_->updateBuffer(*created(r), r.desc, data, bytes, offset);
}

void Device::fillBuffer(Buffer b, uint32_t value) {
  BufferRec& r = buffer(b, "fillBuffer");
  requireContents(r, "fillBuffer");
  if (inPass_)
    throw DeviceError(quoted("fillBuffer", r.desc.name) + ": inside pass '" + pass_->name +
                      "': buffers may only be filled between passes");
  driver_->fillBuffer(*created(r), r.desc, value);
}

Buffer Device::createAccelerationStructure(const std::string& name, Owner owner, Buffer aabbs,
                                           uint32_t boxes) {
  const std::string where = quoted("createAccelerationStructure", labelled(name));
  if (!driver_->info().rayQuery)
    throw DeviceError(where + ": this device offers no ray queries (DeviceInfo::rayQuery)");
  const BufferRec& src = buffer(aabbs, where);
  if (boxes == 0) throw DeviceError(where + ": no boxes");
  if (src.desc.usage != BufferUsage::Storage || src.desc.bytes < std::size_t{boxes} * 24)
    throw DeviceError(where + ": the boxes need a storage buffer of " +
                      std::to_string(std::size_t{boxes} * 24) + " bytes or more; '" +
                      src.desc.name + "' is not one");
  BufferDesc desc{labelled(name), owner, BufferUsage::AccelerationStructure,
                  driver_->accelerationStructureBytes(boxes)};
  auto rec = std::make_unique<BufferRec>(BufferRec{desc, nullptr, group_, aabbs, boxes});
  const uint32_t id = nextId_++;
  buffers_.emplace(id, std::move(rec));
  return Buffer{id};
}

Texture Device::createTexture(const TextureDesc& given) {
  TextureDesc desc = given;
  desc.name = labelled(given.name);
  if (desc.width == 0 || desc.height == 0)
    throw DeviceError(quoted("createTexture", desc.name) + ": zero size (" +
                      std::to_string(desc.width) + "x" + std::to_string(desc.height) + ")");
  if (desc.layers == 0 || desc.layers > kMaxTextureLayers)
    throw DeviceError(quoted("createTexture", desc.name) + ": " + std::to_string(desc.layers) +
                      " layers (1.." + std::to_string(kMaxTextureLayers) + ")");
  // Attachments name no layer of a depth texture: depth arrays are not offered.
  if (desc.layers > 1 && isDepthFormat(desc.format))
    throw DeviceError(quoted("createTexture", desc.name) + ": a depth texture has one layer, not " +
                      std::to_string(desc.layers));
  if (desc.samples != 1) {
    const std::string where =
        quoted("createTexture", desc.name) + ": " + std::to_string(desc.samples) + " samples";
    if (!supportsSamples(desc.samples))
      throw DeviceError(where + ": not a count the device supports (Device::supportsSamples)");
    if (desc.layers != 1)
      throw DeviceError(where + " and " + std::to_string(desc.layers) +
                        " layers (a multisampled texture has one layer)");
    if (isIntegerFormat(desc.format))
      throw DeviceError(where + " of integer format " + formatName(desc.format) +
                        " (integer formats are not multisampled)");
  }
  // Created when first used.
  auto rec = std::make_unique<TextureRec>(TextureRec{desc, nullptr, group_});
  const uint32_t id = nextId_++;
  textures_.emplace(id, std::move(rec));
  return Texture{id};
}

std::string Device::meshPipelineRefusal() const {
  const DeviceInfo i = info();
  if (i.backend == "vulkan" && i.meshShaders) return "";
  const std::string device = i.backend + " on " + i.device + " (driver " + i.driverName + ")";
  return i.backend == "vulkan"
             ? device +
                   " lacks VK_EXT_mesh_shader (Mesa 25.0's lavapipe has it: --driver "
                   "mesa-25.0)"
             : "mesh pipelines are built on Vulkan only (VK_EXT_mesh_shader), not on " + device;
}

Pipeline Device::createPipeline(const PipelineDesc& desc) {
  const std::string where =
      "createPipeline('" + desc.name + "', technique '" + desc.technique + "')";
  const bool compute = desc.compute != nullptr;
  const bool graphics = desc.vertex != nullptr && desc.fragment != nullptr;
  if (compute == (desc.vertex != nullptr || desc.fragment != nullptr) || (!compute && !graphics))
    throw DeviceError(where + ": give either vertex+fragment or compute shaders");
  const bool mesh = graphics && desc.vertex->meshGroupVertices > 0;
  if (mesh)
    if (const std::string why = meshPipelineRefusal(); !why.empty())
      throw DeviceError(where + ": " + why);
  if (graphics && desc.hasDepth && !isDepthFormat(desc.depthFormat))
    throw DeviceError(where + ": depthFormat " + formatName(desc.depthFormat) +
                      " is not a depth format");
  checkColorCount(where, desc.colorFormats.size(), maxColorAttachments_);
  for (Format f : desc.colorFormats)
    if (isDepthFormat(f)) throw DeviceError(where + ": depth format as colour target");
  if (graphics && !supportsSamples(desc.samples))
    throw DeviceError(where + ": " + std::to_string(desc.samples) +
                      " samples: not a count the device supports (Device::supportsSamples)");
  if (desc.blend.size() > desc.colorFormats.size())
    throw DeviceError(where + ": " + std::to_string(desc.blend.size()) + " blend states for " +
                      std::to_string(desc.colorFormats.size()) + " colour targets");
  for (std::size_t i = 0; i < desc.bindings.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (desc.bindings[i].binding == desc.bindings[j].binding)
        throw DeviceError(where + ": binding " + std::to_string(desc.bindings[i].binding) +
                          " declared twice");
  auto rec = std::make_unique<PipelineRec>(PipelineRec{
      desc, deferPipelines_ ? nullptr : driver_->createPipeline(desc), compute, group_, {}, mesh});
  if (deferPipelines_)
    for (const ShaderCode* code : {desc.vertex, desc.fragment, desc.compute})
      if (code) rec->shaders.push_back(*code);
  rec->desc.vertex = rec->desc.fragment = rec->desc.compute = nullptr;
  const uint32_t id = nextId_++;
  pipelines_.emplace(id, std::move(rec));
  return Pipeline{id};
}

template <class Table>
void Device::destroyIn(Table& table, uint32_t id, const char* kind) {
  if (id == 0) return;  // a null handle
  auto& r = record(table, id, kind, "destroy");
  if (inPass_)
    throw DeviceError(quoted("destroy", r.desc.name) + ": inside pass '" + pass_->name + "'");
  if (r.object) driver_->release(std::move(r.object));
  table.erase(id);
}

void Device::destroy(Buffer b) { destroyIn(buffers_, b.id, "buffer"); }

void Device::destroy(Texture t) { destroyIn(textures_, t.id, "texture"); }

void Device::destroy(Pipeline p) { destroyIn(pipelines_, p.id, "pipeline"); }

DriverObject* Device::compiled(PipelineRec& p) {
  if (!p.object) {
    PipelineDesc d = p.desc;
    if (p.compute) {
      d.compute = &p.shaders.at(0);
    } else {
      d.vertex = &p.shaders.at(0);
      d.fragment = &p.shaders.at(1);
    }
    p.object = driver_->createPipeline(d);
    p.shaders.clear();
  }
  return p.object.get();
}

void Device::compilePipelines(const std::set<uint32_t>& ids) {
  for (uint32_t id : ids)
    if (auto it = pipelines_.find(id); it != pipelines_.end()) compiled(*it->second);
}

std::vector<std::pair<std::string, std::string>> Device::compiledPipelines(uint32_t group) const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [id, p] : pipelines_)
    if (p->group == group && p->object) out.push_back({p->desc.name, p->desc.technique});
  return out;
}

std::set<uint32_t> Device::pipelineIdsFrom(uint32_t first) const {
  std::set<uint32_t> ids;
  for (auto it = pipelines_.lower_bound(first); it != pipelines_.end(); ++it) ids.insert(it->first);
  return ids;
}

void Device::destroyGroup(uint32_t group) noexcept {
  if (group == 0 || inFrame_) return;
  auto releaseGroup = [&](auto& table) {
    for (auto it = table.begin(); it != table.end();) {
      if (it->second->group != group) {
        ++it;
        continue;
      }
      try {
        if (it->second->object) driver_->release(std::move(it->second->object));
      } catch (...) {  // a failed release leaks one object; the records still go
      }
      it = table.erase(it);
    }
  };
  releaseGroup(pipelines_);
  releaseGroup(textures_);
  releaseGroup(buffers_);
  try {
    driver_->finishReleases();
  } catch (...) {  // what it deferred is freed later instead
  }
#if defined(__GLIBC__)
  // What the drivers freed with a renderer (their shader compilers' and JITs'
  // many small blocks, across the arenas of their threads) glibc keeps, not
  // the OS: 5-15% of the viewer's resident memory after 22 technique switches
  // on a tiny scene, gone when trimmed. Given back, a long session holds what
  // it uses (a few milliseconds a renderer).
  malloc_trim(0);
#endif
}

void Device::beginFrame() {
  if (inFrame_) throw DeviceError("beginFrame: a frame is already being recorded");
  driver_->beginFrame();
  inFrame_ = true;
  frameWork_.clear();
}

void Device::beginPass(const PassDesc& pd) {
  const std::string name = labelled(pd.name);
  if (hook_) hook_->beforePass(name);
  const std::string where = quoted("beginPass", name);
  requireFrame(where, true, false);
  checkColorCount(where, pd.color.size(), maxColorAttachments_);
  auto open = std::make_unique<OpenPass>();
  open->name = name;
  DriverPass dp;
  dp.name = name;
  dp.color.reserve(pd.color.size());  // resolveTargets points into it
  struct ResolveTarget {
    DriverColorTarget* target;
    TextureRec* from;
    Texture to;
  };
  std::vector<ResolveTarget> resolveTargets;
  auto size = [&](const TextureRec& t) {
    if (dp.width == 0) {
      dp.width = t.desc.width;
      dp.height = t.desc.height;
    } else if (dp.width != t.desc.width || dp.height != t.desc.height) {
      throw DeviceError(where + ": attachments differ in size ('" + t.desc.name + "' is " +
                        std::to_string(t.desc.width) + "x" + std::to_string(t.desc.height) +
                        ", the pass " + std::to_string(dp.width) + "x" + std::to_string(dp.height) +
                        ")");
    }
  };
  auto attach = [&](Texture tex, uint32_t layer) -> TextureRec& {
    TextureRec& t = texture(tex, where);
    if (layer >= t.desc.layers)
      throw DeviceError(where + ": layer " + std::to_string(layer) + " of texture '" + t.desc.name +
                        "' is out of range (it has " + std::to_string(t.desc.layers) + ")");
    for (std::size_t i = 0; i < open->attachments.size(); ++i)
      if (open->attachments[i] == tex.id && open->attachmentLayers[i] == layer)
        throw DeviceError(where + ": texture '" + t.desc.name + "'" +
                          (t.desc.layers > 1 ? " layer " + std::to_string(layer) : "") +
                          " attached twice");
    open->attachments.push_back(tex.id);
    open->attachmentLayers.push_back(layer);
    size(t);
    // One sample count for the whole pass: the rasterizer has one.
    if (open->samples == 0) {
      open->samples = t.desc.samples;
    } else if (open->samples != t.desc.samples) {
      throw DeviceError(where + ": attachments differ in sample count ('" + t.desc.name + "' has " +
                        std::to_string(t.desc.samples) + ", the pass " +
                        std::to_string(open->samples) + ")");
    }
    return t;
  };
  for (const ColorAttachment& a : pd.color) {
    TextureRec& t = attach(a.texture, a.layer);
    if (isDepthFormat(t.desc.format))
      throw DeviceError(where + ": depth texture '" + t.desc.name + "' as colour attachment");
    open->colorFormats.push_back(t.desc.format);
    dp.color.push_back({{created(t), &t.desc}, a.load, a.clear, a.clearUint, a.layer, {}});
    if (a.resolve) resolveTargets.push_back({&dp.color.back(), &t, a.resolve});
  }
  if (pd.depth.texture) {
    TextureRec& t = attach(pd.depth.texture, 0);
    if (!isDepthFormat(t.desc.format))
      throw DeviceError(where + ": '" + t.desc.name + "' is not a depth texture");
    open->hasDepth = true;
    dp.depth = {created(t), &t.desc};
    dp.depthLoad = pd.depth.load;
    dp.depthClear = pd.depth.clear;
  }
  if (open->attachments.empty()) {
    if (pd.width == 0 || pd.height == 0) throw DeviceError(where + ": no attachments and no size");
    dp.width = pd.width;
    dp.height = pd.height;
  }
  if (open->samples == 0) open->samples = 1;
  dp.samples = open->samples;
  // Resolve targets: single-sampled, of the attachment's format and size,
  // neither attached nor resolved into twice (checked after every attachment
  // is known, so a target that is also an attachment is caught).
  std::vector<uint32_t> resolved;
  for (auto& [target, from, tex] : resolveTargets) {
    TextureRec& r = texture(tex, where);
    const std::string what =
        where + ": resolve of '" + from->desc.name + "' into '" + r.desc.name + "'";
    if (from->desc.samples == 1) throw DeviceError(what + ": the attachment is not multisampled");
    if (r.desc.samples != 1 || r.desc.layers != 1)
      throw DeviceError(what + ": the target must be single-sampled with one layer");
    if (r.desc.format != from->desc.format)
      throw DeviceError(what + ": formats differ (" + formatName(from->desc.format) + ", " +
                        formatName(r.desc.format) + ")");
    if (r.desc.width != from->desc.width || r.desc.height != from->desc.height)
      throw DeviceError(what + ": sizes differ");
    // (An attachment of the pass is multisampled, so it failed above.)
    if (std::count(resolved.begin(), resolved.end(), tex.id))
      throw DeviceError(what + ": the target is resolved into twice");
    resolved.push_back(tex.id);
    target->resolve = {created(r), &r.desc};
  }
  open->attachments.insert(open->attachments.end(), resolved.begin(), resolved.end());
  for (Texture s : pd.sampledTextures) {
    TextureRec& t = texture(s, where);
    if (std::count(open->attachments.begin(), open->attachments.end(), s.id))
      throw DeviceError(where + ": texture '" + t.desc.name +
                        "' is both an attachment and sampled");
    if (std::count(open->sampled.begin(), open->sampled.end(), s.id)) continue;
    if (t.desc.samples != 1)
      throw DeviceError(where + ": texture '" + t.desc.name + "' is multisampled (" +
                        std::to_string(t.desc.samples) +
                        " samples) and cannot be sampled: resolve it (ColorAttachment::resolve)");
    open->sampled.push_back(s.id);
    dp.sampled.push_back({created(t), &t.desc});
  }
  // The work counters: what the pass writes (each attachment's layer, the
  // resolve targets) and reads (attachments it loads; sampling is counted by
  // the draws that bind it).
  PassWork& w = open->work;
  auto attached = [&](Texture tex, uint32_t layer, LoadOp load) {
    const TextureDesc& d = texture(tex, where).desc;
    touch(w, open->touched, 'w', tex.id, layer, textureTouch(d, 1, "write"));
    if (load == LoadOp::Load)
      touch(w, open->touched, 'l', tex.id, layer, textureTouch(d, 1, "read"));
  };
  for (const ColorAttachment& a : pd.color) {
    attached(a.texture, a.layer, a.load);
    if (a.resolve) attached(a.resolve, 0, LoadOp::Clear);
  }
  if (pd.depth.texture) attached(pd.depth.texture, 0, pd.depth.load);
  driver_->beginPass(dp);
  pass_ = std::move(open);
  inPass_ = true;
}

// Checks `given` against the pipeline's declared slots and resolves it, in
// slot order, to driver objects.
std::vector<DriverBinding> Device::resolve(const PipelineRec& p, const std::vector<Binding>& given,
                                           const std::string& where, bool inPass,
                                           OpenPass& counted) {
  for (std::size_t i = 0; i < given.size(); ++i) {
    const uint32_t n = given[i].binding;
    if (std::none_of(p.desc.bindings.begin(), p.desc.bindings.end(),
                     [&](const BindingSlot& s) { return s.binding == n; }))
      throw DeviceError(where + ": binding " + std::to_string(n) +
                        " is not declared in the pipeline");
    for (std::size_t j = 0; j < i; ++j)
      if (given[j].binding == n)
        throw DeviceError(where + ": binding " + std::to_string(n) + " given twice");
  }
  std::vector<DriverBinding> out;
  for (const BindingSlot& s : p.desc.bindings) {
    auto it = std::find_if(given.begin(), given.end(),
                           [&](const Binding& b) { return b.binding == s.binding; });
    const std::string slot = where + ": binding " + std::to_string(s.binding);
    if (it == given.end()) throw DeviceError(slot + " not provided");
    if (s.kind == BindingKind::SampledTexture || s.kind == BindingKind::SampledTextureArray) {
      if (!it->texture || it->buffer) throw DeviceError(slot + " needs a texture");
      TextureRec& t = texture(it->texture, where);
      if (t.desc.samples != 1)
        throw DeviceError(slot + ": texture '" + t.desc.name +
                          "' is multisampled and cannot be sampled: resolve it");
      if (s.kind == BindingKind::SampledTexture && t.desc.layers > 1)
        throw DeviceError(slot + ": texture '" + t.desc.name + "' has " +
                          std::to_string(t.desc.layers) +
                          " layers (a sampler2D slot; arrays need SampledTextureArray)");
      if (inPass && !std::count(pass_->sampled.begin(), pass_->sampled.end(), it->texture.id))
        throw DeviceError(where + ": texture '" + t.desc.name + "' is sampled but pass '" +
                          pass_->name + "' does not list it in sampledTextures");
      out.push_back({s.binding, s.kind, created(t), nullptr, &t.desc});
      const uint32_t layers = s.kind == BindingKind::SampledTexture ? 1 : t.desc.layers;
      touch(counted.work, counted.touched, 't', it->texture.id, 0,
            textureTouch(t.desc, layers, "read"));
    } else {
      if (!it->buffer || it->texture) throw DeviceError(slot + " needs a buffer");
      BufferRec& b = buffer(it->buffer, where);
      const bool structure = b.desc.usage == BufferUsage::AccelerationStructure;
      if (structure != (s.kind == BindingKind::AccelerationStructure))
        throw DeviceError(slot + ": buffer '" + b.desc.name + "' " +
                          (structure
                               ? "is an acceleration structure (an AccelerationStructure slot)"
                               : "is not an acceleration structure"));
      out.push_back({s.binding, s.kind, created(b), &b.desc, nullptr});
      const bool storage = s.kind == BindingKind::StorageBuffer;
      touch(counted.work, counted.touched, 'b', it->buffer.id, 0,
            {b.desc.name, "buffer", 0, 0, 0, 0, b.desc.bytes, storage ? "storage" : "read"});
    }
  }
  return out;
}

void Device::draw(Pipeline pipe, const std::vector<Binding>& bindings, uint32_t vertexCount,
                  uint32_t instanceCount) {
  PipelineRec& p = pipeline(pipe, "draw");
  const std::string where = quoted("draw", p.desc.name);
  requireFrame(where, true, true);
  if (p.compute) throw DeviceError(where + ": a compute pipeline (use dispatch)");
  if (p.desc.colorFormats != pass_->colorFormats || p.desc.hasDepth != pass_->hasDepth)
    throw DeviceError(where + ": the pipeline's targets do not match pass '" + pass_->name +
                      "' (colour formats and depth must be the same)");
  if (p.desc.samples != pass_->samples)
    throw DeviceError(where + ": the pipeline has " + std::to_string(p.desc.samples) +
                      " samples, pass '" + pass_->name + "' " + std::to_string(pass_->samples) +
                      " (they must be the same)");
  if (p.mesh && instanceCount != 1)
    throw DeviceError(where + ": a mesh pipeline draws one instance (" +
                      std::to_string(instanceCount) + " asked)");
  const auto resolved = resolve(p, bindings, where, true, *pass_);
  ++pass_->work.draws;
  driver_->draw(*compiled(p), p.desc, resolved, vertexCount, instanceCount);
}

void Device::endPass() {
  if (!inPass_) throw DeviceError("endPass: no pass is open");
  inPass_ = false;
  frameWork_.push_back(std::move(pass_->work));
  driver_->endPass();
}

void Device::dispatch(const std::string& givenName, Pipeline pipe,
                      const std::vector<Binding>& bindings, uint32_t x, uint32_t y, uint32_t z) {
  const std::string passName = labelled(givenName);
  if (hook_) hook_->beforePass(passName);
  const std::string where = quoted("dispatch", passName);
  requireFrame(where, true, false);
  PipelineRec& p = pipeline(pipe, where);
  if (!p.compute) throw DeviceError(where + ": '" + p.desc.name + "' is not a compute pipeline");
  OpenPass counted;
  const auto resolved = resolve(p, bindings, where, false, counted);
  counted.work.dispatches = 1;
  frameWork_.push_back(std::move(counted.work));
  driver_->dispatch(passName, *compiled(p), p.desc, resolved, x, y, z);
}

void Device::endFrame() {
  if (!inFrame_) throw DeviceError("endFrame: no frame is being recorded");
  if (inPass_) throw DeviceError("endFrame: pass '" + pass_->name + "' is still open");
  inFrame_ = false;  // whatever happens below, the frame is over
  namingAllocation("running the frame's work", 0, [&] {
    driver_->endFrame();
    return 0;
  });
  // The driver's timings are in pass order, one per pass or dispatch, with the
  // API's counts; the front end adds its own.
  lastTimings_ = driver_->lastFrameTimings();
  if (lastTimings_.size() != frameWork_.size())
    throw DeviceError("endFrame: the driver timed " + std::to_string(lastTimings_.size()) +
                      " passes, the frame had " + std::to_string(frameWork_.size()));
  for (std::size_t i = 0; i < lastTimings_.size(); ++i) lastTimings_[i].work += frameWork_[i];
}

std::vector<PassTiming> Device::lastFrameTimings() const { return lastTimings_; }

std::vector<uint8_t> Device::readTexture(Texture t) {
  TextureRec& r = texture(t, "readTexture");
  requireFrame(quoted("readTexture", r.desc.name), false, false);
  requireSingleSampled(r.desc, "readTexture");
  DriverObject* object = created(r);
  return namingAllocation("reading back texture '" + r.desc.name + "'", textureBytes(r.desc),
                          [&] { return driver_->readTexture(*object, r.desc); });
}

std::vector<uint8_t> Device::readBuffer(Buffer b) {
  BufferRec& r = buffer(b, "readBuffer");
  requireContents(r, "readBuffer");
  requireFrame(quoted("readBuffer", r.desc.name), false, false);
  if (!r.object && !r.pending.empty()) return r.pending;  // its contents, not made yet
  DriverObject* object = created(r);
  return namingAllocation("reading back buffer '" + r.desc.name + "'", r.desc.bytes,
                          [&] { return driver_->readBuffer(*object, r.desc); });
}

void Device::writeTexture(Texture t, const std::vector<uint8_t>& bytes) {
  TextureRec& r = texture(t, "writeTexture");
  const std::string where = quoted("writeTexture", r.desc.name);
  requireFrame(where, false, false);
  requireSingleSampled(r.desc, "writeTexture");
  const std::size_t want =
      std::size_t{r.desc.width} * r.desc.height * r.desc.layers * bytesPerPixel(r.desc.format);
  if (bytes.size() != want)
    throw DeviceError(where + ": " + std::to_string(bytes.size()) +
                      " bytes given, the texture holds " + std::to_string(want));
  driver_->writeTexture(*created(r), r.desc, bytes);
}

Window* Device::window() { return driver_->window(); }

bool Device::present(Texture t, PresentedImage* capture) {
  TextureRec& r = texture(t, "present");
  const std::string where = quoted("present", r.desc.name);
  requireFrame(where, false, false);
  requireSingleSampled(r.desc, "present");
  if (isDepthFormat(r.desc.format) || isIntegerFormat(r.desc.format))
    throw DeviceError(where + ": a " + formatName(r.desc.format) +
                      " texture cannot be shown (a float or unorm colour texture can)");
  if (r.desc.layers != 1)
    throw DeviceError(where + ": an array of " + std::to_string(r.desc.layers) +
                      " layers cannot be shown (one layer can)");
  if (!driver_->window())
    throw DeviceError(where + ": the " + driver_->info().platform +
                      " platform has no window (use --platform window)");
  return driver_->present(*created(r), r.desc, capture);
}

TextureDesc Device::describe(Texture t) const { return texture(t, "describe").desc; }

BufferDesc Device::describe(Buffer b) const { return buffer(b, "describe").desc; }

}  // namespace sb
