#include "render/graph/pass.h"

#include <stdexcept>

namespace sb {

Inputs& Inputs::uniform(uint32_t slot, Buffer b) {
  inputs_.push_back({{slot, BindingKind::UniformBuffer}, b, {}, false});
  return *this;
}

Inputs& Inputs::readStorage(uint32_t slot, Buffer b) {
  inputs_.push_back({{slot, BindingKind::StorageBuffer}, b, {}, false});
  return *this;
}

Inputs& Inputs::storage(uint32_t slot, Buffer b) {
  inputs_.push_back({{slot, BindingKind::StorageBuffer}, b, {}, true});
  return *this;
}

Inputs& Inputs::sideOutput(uint32_t slot, Buffer b) {
  inputs_.push_back({{slot, BindingKind::StorageBuffer}, b, {}, false, true});
  return *this;
}

Inputs& Inputs::accelerationStructure(uint32_t slot, Buffer as) {
  inputs_.push_back({{slot, BindingKind::AccelerationStructure}, as, {}, false});
  return *this;
}

Inputs& Inputs::sample(uint32_t slot, Texture t) {
  inputs_.push_back({{slot, BindingKind::SampledTexture}, {}, t, false});
  return *this;
}

Inputs& Inputs::sampleArray(uint32_t slot, Texture t) {
  inputs_.push_back({{slot, BindingKind::SampledTextureArray}, {}, t, false});
  return *this;
}

Inputs& Inputs::add(const Inputs& more) {
  inputs_.insert(inputs_.end(), more.inputs_.begin(), more.inputs_.end());
  return *this;
}

Inputs& Inputs::replaceBuffer(uint32_t slot, Buffer b) {
  for (Input& i : inputs_)
    if (i.slot.binding == slot && !i.texture) {
      i.buffer = b;
      return *this;
    }
  throw std::logic_error("Inputs::replaceBuffer: no buffer at slot " + std::to_string(slot));
}

std::vector<BindingSlot> Inputs::slots() const {
  std::vector<BindingSlot> out;
  for (const Input& i : inputs_) out.push_back(i.slot);
  return out;
}

std::vector<Binding> Inputs::bindings() const {
  std::vector<Binding> out;
  for (const Input& i : inputs_) out.push_back({i.slot.binding, i.buffer, i.texture});
  return out;
}

std::vector<Texture> Inputs::sampled() const {
  std::vector<Texture> out;
  for (const Input& i : inputs_)
    if (i.texture) out.push_back(i.texture);
  return out;
}

std::vector<GraphResource> Inputs::reads() const {
  std::vector<GraphResource> out;
  for (const Input& i : inputs_)
    out.push_back(i.texture ? GraphResource::of(i.texture) : GraphResource::of(i.buffer));
  return out;
}

std::vector<GraphResource> Inputs::writes() const {
  std::vector<GraphResource> out;
  for (const Input& i : inputs_)
    if (i.written) out.push_back(GraphResource::of(i.buffer));
  return out;
}

std::vector<GraphResource> Inputs::sideWrites() const {
  std::vector<GraphResource> out;
  for (const Input& i : inputs_)
    if (i.side) out.push_back(GraphResource::of(i.buffer));
  return out;
}

Pass& Pass::color(Texture t, LoadOp load, std::array<float, 4> clear, uint32_t layer) {
  desc_.color.push_back({t, load, clear, {}, layer, {}});
  return *this;
}

Pass& Pass::resolveInto(Texture target) {
  if (!desc_.color.empty()) desc_.color.back().resolve = target;
  return *this;
}

Pass& Pass::colorOver(Texture t, bool over, glm::vec3 background) {
  return color(t, over ? LoadOp::Load : LoadOp::Clear,
               {background.r, background.g, background.b, 1.0f});
}

Pass& Pass::colorUint(Texture t, LoadOp load, std::array<uint32_t, 4> clear, uint32_t layer) {
  desc_.color.push_back({t, load, {}, clear, layer, {}});
  return *this;
}

Pass& Pass::depth(Texture t, LoadOp load, float clear) {
  desc_.depth = {t, load, clear};
  depthWritten_ = true;
  return *this;
}

Pass& Pass::depthReadOnly(Texture t) {
  desc_.depth = {t, LoadOp::Load, 1.0f};
  depthWritten_ = false;
  return *this;
}

Pass& Pass::size(uint32_t width, uint32_t height) {
  desc_.width = width;
  desc_.height = height;
  return *this;
}

Pass& Pass::uniform(uint32_t slot, Buffer b) {
  inputs_.uniform(slot, b);
  return *this;
}

Pass& Pass::readStorage(uint32_t slot, Buffer b) {
  inputs_.readStorage(slot, b);
  return *this;
}

Pass& Pass::storage(uint32_t slot, Buffer b) {
  inputs_.storage(slot, b);
  return *this;
}

Pass& Pass::sample(uint32_t slot, Texture t) {
  inputs_.sample(slot, t);
  return *this;
}

Pass& Pass::sampleArray(uint32_t slot, Texture t) {
  inputs_.sampleArray(slot, t);
  return *this;
}

Pass& Pass::inputs(const Inputs& more) {
  inputs_.add(more);
  return *this;
}

PassDesc Pass::desc() const {
  PassDesc d = desc_;
  d.name = name_;
  d.sampledTextures = inputs_.sampled();
  return d;
}

PipelineDesc Pass::pipeline(const Device& dev, std::string name, std::string technique) const {
  PipelineDesc d;
  d.name = std::move(name);
  d.technique = std::move(technique);
  d.bindings = slots();
  uint32_t samples = 0;
  auto describe = [&](Texture t, const std::string& what) {
    if (!t)
      throw std::logic_error("pass '" + name_ + "': pipeline '" + d.name + "' made before its " +
                             what + " texture (create the textures first)");
    const TextureDesc td = dev.describe(t);
    if (samples != 0 && td.samples != samples)
      throw std::logic_error("pass '" + name_ + "': its attachments differ in sample count ('" +
                             td.name + "' has " + std::to_string(td.samples) + ", the others " +
                             std::to_string(samples) + ")");
    samples = td.samples;
    return td;
  };
  for (std::size_t i = 0; i < desc_.color.size(); ++i)
    d.colorFormats.push_back(
        describe(desc_.color[i].texture, "colour attachment " + std::to_string(i)).format);
  if (desc_.depth.texture) {
    d.depthFormat = describe(desc_.depth.texture, "depth attachment").format;
    d.hasDepth = d.depthTest = true;
    d.depthWrite = depthWritten_;
  }
  if (samples != 0) d.samples = samples;
  return d;
}

std::vector<GraphResource> Pass::reads() const {
  std::vector<GraphResource> out = inputs_.reads();
  for (const ColorAttachment& a : desc_.color)
    if (a.load == LoadOp::Load) out.push_back(GraphResource::of(a.texture));
  if (desc_.depth.texture && desc_.depth.load == LoadOp::Load)
    out.push_back(GraphResource::of(desc_.depth.texture));
  return out;
}

std::vector<GraphResource> Pass::writes() const {
  std::vector<GraphResource> out = inputs_.writes();
  for (const ColorAttachment& a : desc_.color) {
    out.push_back(GraphResource::of(a.texture));
    if (a.resolve) out.push_back(GraphResource::of(a.resolve));
  }
  if (desc_.depth.texture && depthWritten_) out.push_back(GraphResource::of(desc_.depth.texture));
  return out;
}

void Pass::draw(Device& dev, Pipeline p, uint32_t vertexCount, uint32_t instanceCount) const {
  dev.beginPass(desc());
  if (p) dev.draw(p, bindings(), vertexCount, instanceCount);
  dev.endPass();
}

void Pass::draw(Device& dev, const std::vector<Draw>& draws) const {
  dev.beginPass(desc());
  const std::vector<Binding> b = bindings();
  for (const Draw& d : draws)
    if (d.pipeline) dev.draw(d.pipeline, b, d.vertexCount);
  dev.endPass();
}

void Pass::dispatch(Device& dev, Pipeline p, uint32_t x, uint32_t y, uint32_t z) const {
  dev.dispatch(name_, p, bindings(), x, y, z);
}

}  // namespace sb
