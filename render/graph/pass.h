// A pass declared once. A technique says what each pass writes (attachments,
// storage), samples and binds, by slot; from that one declaration follow the
// pipeline's binding slots (slots()), the draw's bindings (bindings()), the
// device pass (desc(), with the textures it samples) and the frame graph's
// edges (reads(), writes()) and the pipelines drawing in it (pipeline(): their
// attachment formats, samples, depth state and slots). A technique builds the
// declaration in one member function and calls it both when it makes the
// pipeline and when it adds the pass to the graph; its attachments' textures
// must exist by the time it makes the pipeline.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "backends/device.h"

namespace sb {

// A device resource as the frame graph sees it: textures and buffers share one
// id space on the Device.
struct GraphResource {
  uint32_t id = 0;
  bool texture = false;
  static GraphResource of(Texture t) { return {t.id, true}; }
  static GraphResource of(Buffer b) { return {b.id, false}; }
  bool operator==(const GraphResource& o) const { return id == o.id; }
  bool operator<(const GraphResource& o) const { return id < o.id; }
};

// What a pass's shaders bind, by slot.
class Inputs {
 public:
  Inputs& uniform(uint32_t slot, Buffer b);
  Inputs& readStorage(uint32_t slot, Buffer b);  // a storage buffer only read
  Inputs& storage(uint32_t slot, Buffer b);      // a storage buffer read and written
  // A storage buffer the shaders add to on the side (a counter of capped
  // rays): written, yet what writes it is not needed for it. The graph sees a
  // read (the pass that cleared it stays before it) and a side write
  // (sideWrites), never a write, so it keeps no pass alive.
  Inputs& sideOutput(uint32_t slot, Buffer b);
  // An acceleration structure (Device::createAccelerationStructure), read.
  Inputs& accelerationStructure(uint32_t slot, Buffer as);
  Inputs& sample(uint32_t slot, Texture t);       // sampler2D
  Inputs& sampleArray(uint32_t slot, Texture t);  // sampler2DArray
  Inputs& add(const Inputs& more);
  // The buffer bound at `slot` swapped for `b` (e.g. a subset of the scene's
  // segments); the slot must be bound already (std::logic_error otherwise).
  Inputs& replaceBuffer(uint32_t slot, Buffer b);

  std::vector<BindingSlot> slots() const;
  std::vector<Binding> bindings() const;
  std::vector<Texture> sampled() const;
  std::vector<GraphResource> reads() const;
  std::vector<GraphResource> writes() const;
  std::vector<GraphResource> sideWrites() const;

 private:
  struct Input {
    BindingSlot slot;
    Buffer buffer;
    Texture texture;
    bool written = false;
    bool side = false;  // sideOutput
  };
  std::vector<Input> inputs_;
};

class Pass {
 public:
  explicit Pass(std::string name) : name_(std::move(name)) {}

  // What it writes. An attachment loaded (LoadOp::Load) is also read.
  Pass& color(Texture t, LoadOp load, std::array<float, 4> clear = {}, uint32_t layer = 0);
  Pass& colorUint(Texture t, LoadOp load, std::array<uint32_t, 4> clear = {}, uint32_t layer = 0);
  // A final pass's colour target: drawn over what it holds when `over` (the opaque image was
  // drawn first), else cleared to the opaque background.
  Pass& colorOver(Texture t, bool over, glm::vec3 background);
  // The last colour attachment (multisampled) is averaged into `target` at the
  // end of the pass (ColorAttachment::resolve): the pass writes it too.
  Pass& resolveInto(Texture target);
  Pass& depth(Texture t, LoadOp load, float clear = 1.0f);
  // A depth attachment only tested against (loaded, never written): a read.
  Pass& depthReadOnly(Texture t);
  Pass& size(uint32_t width, uint32_t height);  // a pass without attachments

  // What its shaders bind (see Inputs; side outputs and acceleration structures
  // through inputs()).
  Pass& uniform(uint32_t slot, Buffer b);
  Pass& readStorage(uint32_t slot, Buffer b);
  Pass& storage(uint32_t slot, Buffer b);
  Pass& sample(uint32_t slot, Texture t);
  Pass& sampleArray(uint32_t slot, Texture t);
  Pass& inputs(const Inputs& more);

  const std::string& name() const { return name_; }
  const Inputs& inputs() const { return inputs_; }
  std::vector<BindingSlot> slots() const { return inputs_.slots(); }
  std::vector<Binding> bindings() const { return inputs_.bindings(); }
  PassDesc desc() const;
  // A pipeline drawing in this pass, its targets from the declaration: colour
  // formats (of the colour attachments' textures, in order), samples (of the
  // attachments, which must agree), depth (present, tested and with the depth
  // texture's format when the pass has a depth attachment; written when it is
  // depth(), not depthReadOnly()) and binding slots (slots()). A pass without
  // attachments (size(), or a compute dispatch) gives only the slots. The
  // technique sets the shaders, topology, blend, compare op and anything else
  // special (e.g. depthWrite off over a written depth attachment).
  // std::logic_error, naming the pass, when an attachment's texture is not
  // made yet or the attachments' sample counts differ.
  PipelineDesc pipeline(const Device& dev, std::string name, std::string technique = {}) const;
  std::vector<GraphResource> reads() const;
  std::vector<GraphResource> writes() const;
  std::vector<GraphResource> sideWrites() const { return inputs_.sideWrites(); }

  // Records it: a render pass with one draw (none when the pipeline is empty,
  // e.g. a scene without hair: the pass then only clears its targets) ...
  void draw(Device& dev, Pipeline p, uint32_t vertexCount, uint32_t instanceCount = 1) const;
  // ... or several (e.g. the mesh and the hair into one target) ...
  struct Draw {
    Pipeline pipeline;
    uint32_t vertexCount = 0;
  };
  void draw(Device& dev, const std::vector<Draw>& draws) const;
  // ... or a compute dispatch.
  void dispatch(Device& dev, Pipeline p, uint32_t x, uint32_t y = 1, uint32_t z = 1) const;

 private:
  std::string name_;
  PassDesc desc_;
  bool depthWritten_ = false;
  Inputs inputs_;
};

}  // namespace sb
