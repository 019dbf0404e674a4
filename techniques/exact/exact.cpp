#include "techniques/exact/exact.h"

#include "render/common/peel_uniforms.h"
#include "render/common/readback.h"
#include "render/common/shader_library.h"
#include "techniques/exact/uniforms.h"

namespace sb {

namespace {
// Binding numbers, as in techniques/exact/exact.glsl.
// 15 is the opaque mesh's depth map (OpaqueShadow).
constexpr uint32_t kParams = SB_SLOT_EXACT_PARAMS, kCounts = SB_SLOT_EXACT_COUNTS,
                   kOffsets = SB_SLOT_EXACT_OFFSETS, kCursor = SB_SLOT_EXACT_CURSOR,
                   kNodes = SB_SLOT_EXACT_NODES, kState = SB_SLOT_EXACT_STATE,
                   kStatus = SB_SLOT_EXACT_STATUS;
constexpr uint32_t kSize = SB_SLOT_PEEL_ADVANCE_SIZE;  // peel_advance.comp's size uniform

}  // namespace

ExactShadow::ExactShadow(Method method, uint32_t size, float bias, uint32_t maxLayers)
    : method_(method), size_(size), bias_(bias), maxLayers_(maxLayers) {}

void ExactShadow::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  scene_ = &scene;
  settings_ = s;
  const std::size_t texels = std::size_t(size_) * size_;
  const ViewUniforms view = lightView(s, size_, size_);
  lightView_ = createLightViewBuffer(dev, view, "exact");
  params_ = createLightLookupParams<ExactShadowParams>(dev, view, bias_, size_, scene.shadowAlpha,
                                                       "exact");
  const PeelSize sizeData{glm::uvec4(uint32_t(texels), size_, 0, 0)};
  sizeUbo_ = dev.createBuffer({"exact.size", Owner::Frame, BufferUsage::Uniform, sizeof sizeData},
                              &sizeData);
  counts_ = dev.createBuffer({"exact.counts", Owner::Shadow, BufferUsage::Storage, texels * 4});
  offsets_ = dev.createBuffer({"exact.offsets", Owner::Shadow, BufferUsage::Storage, texels * 4});
  cursor_ = dev.createBuffer({"exact.cursor", Owner::Shadow, BufferUsage::Storage, texels * 4});
  status_ = dev.createBuffer({"exact.status", Owner::Shadow, BufferUsage::Storage, 16});
  // Sized by prepare()'s count; declared now so that the frame graph is built
  // (and culled) before any preparation runs.
  nodes_ = dev.createBuffer({"exact.nodes", Owner::Shadow, BufferUsage::Storage, 8});
  if (method_ == Method::Peel)
    state_ =
        dev.createBuffer({"exact.peel_state", Owner::Shadow, BufferUsage::Storage, texels * 16});
  else
    state_ = dev.createBuffer({"exact.peel_state", Owner::Shadow, BufferUsage::Storage, 16});
  opaque_.setup(dev, scene, size_, lightView_, "exact");

  count_ = makeHairCountPipeline(dev, s, countPass(), kCounts, "exact");
  const ShaderCode vert = Geometry::strandVertexShader(s);
  PipelineDesc d = listPass("exact.fill").pipeline(dev, "exact.fill", "exact");
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  if (method_ == Method::ABuffer) {
    const ShaderCode frag = loadShader("techniques/exact/fill.frag");
    d.fragment = &frag;
    fill_ = dev.createPipeline(d);
    ShaderDefines order;
    if (bySubmission_) order.defines.push_back({"SB_EXACT_BY_SUBMISSION", "1"});
    const ShaderCode comp = loadShader("techniques/exact/sort.comp", order);
    PipelineDesc c = sortPass().pipeline(dev, "exact.sort", "exact");
    c.compute = &comp;
    sort_ = dev.createPipeline(c);
  } else {
    for (int pass = 0; pass < 2; ++pass) {
      ShaderDefines defs;
      defs.defines.push_back({"SB_PEEL_PASS", std::to_string(pass)});
      const ShaderCode frag = loadShader("techniques/exact/peel.frag", defs);
      d.name = pass == 0 ? "exact.peel.depth" : "exact.peel.id";
      d.fragment = &frag;
      (pass == 0 ? peel0_ : peel1_) = dev.createPipeline(d);
    }
    advance_ =
        makePeelAdvancePipeline(dev, advancePass(), kState, kCursor, kOffsets, kNodes, "exact");
  }
}

void ExactShadow::prepare(Device& dev) {
  // Count the fragments of every texel once: it sizes the lists and the
  // number of peel layers (in place of an occlusion query per layer).
  dev.fillBuffer(counts_, 0);
  dev.beginFrame();
  countPass().draw(dev, count_, Geometry::strandVertexCount(*scene_, settings_));
  dev.endFrame();
  const ListLayout layout = layoutFromCounts(dev.readBuffer(counts_));
  complexity_ = layout.complexity;
  dev.updateBuffer(offsets_, layout.offsets.data(), layout.offsets.size() * 4);
  const std::size_t nodes = std::max<uint64_t>(layout.complexity.total, 1);
  dev.setBufferSize(nodes_, nodes * 8);
  layers_ = std::min(complexity_.max, maxLayers_);
}

// The fragment lists and their parameters: every pass of the technique binds
// them all (and writes them); the lookup reads them.
Inputs ExactShadow::lists(bool written) const {
  Inputs in;
  auto storage = [&](uint32_t slot, Buffer b) {
    written ? in.storage(slot, b) : in.readStorage(slot, b);
  };
  in.uniform(kParams, params_);
  storage(kCounts, counts_);
  storage(kOffsets, offsets_);
  storage(kCursor, cursor_);
  storage(kNodes, nodes_);
  storage(kState, state_);
  storage(kStatus, status_);
  return in;
}

Inputs ExactShadow::sortedLists() const {
  Inputs in;
  in.readStorage(kCounts, counts_)
      .readStorage(kOffsets, offsets_)
      .readStorage(kCursor, cursor_)
      .readStorage(kNodes, nodes_);
  return in;
}

// A hair pass from the light into the lists (no attachments: the light map's size).
Pass ExactShadow::listPass(const std::string& name) const {
  return Pass(name)
      .size(size_, size_)
      .inputs(Geometry::inputs(*scene_, lightView_))
      .inputs(lists(true));
}

Pass ExactShadow::countPass() const {
  return Pass("exact.count")
      .size(size_, size_)
      .inputs(Geometry::inputs(*scene_, lightView_))
      .storage(kCounts, counts_);
}

Pass ExactShadow::sortPass() const { return Pass("exact.sort").inputs(lists(true)); }

Pass ExactShadow::advancePass() const {
  return Pass("exact.peel.advance")
      .uniform(kSize, sizeUbo_)
      .storage(kState, state_)
      .storage(kCursor, cursor_)
      .storage(kOffsets, offsets_)
      .storage(kNodes, nodes_);
}

void ExactShadow::addPasses(FrameGraph& graph, Device& dev) {
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  const uint32_t texels = size_ * size_;
  opaque_.addPass(graph, dev);
  if (method_ == Method::ABuffer) {
    const Pass fill = listPass("exact.fill"), sort = sortPass();
    graph.add("exact.fill", {fill, sort}, [this, &dev, vertices, texels, fill, sort] {
      dev.fillBuffer(cursor_, 0);
      dev.fillBuffer(status_, 0);
      fill.draw(dev, fill_, vertices);
      const glm::uvec2 g = dispatchGroups(texels);
      sort.dispatch(dev, sort_, g.x, g.y);
    });
    return;
  }
  const Pass depth = listPass("exact.peel.depth"), id = listPass("exact.peel.id"),
             advance = advancePass();
  graph.add("exact.peel", {depth, id, advance}, [this, &dev, vertices, texels, depth, id, advance] {
    dev.fillBuffer(cursor_, 0);
    dev.fillBuffer(state_, 0xFFFFFFFFu);
    for (uint32_t layer = 0; layer < layers_; ++layer) {
      depth.draw(dev, peel0_, vertices);
      id.draw(dev, peel1_, vertices);
      const glm::uvec2 g = dispatchGroups(texels);
      advance.dispatch(dev, advance_, g.x, g.y);
    }
  });
}

void ExactShadow::addTexelPass(FrameGraph& graph, Device& dev, const Pass& pass, Pipeline pipeline,
                               Buffer status) const {
  const uint32_t texels = size_ * size_;
  graph.add(pass, [&dev, texels, pass, pipeline, status] {
    dev.fillBuffer(status, 0);
    const glm::uvec2 g = dispatchGroups(texels);
    pass.dispatch(dev, pipeline, g.x, g.y);
  });
}

ShadowLookup ExactShadow::lookup() const {
  ShadowLookup l{"techniques/exact/lookup.glsl"};
  l.defines.defines.push_back({"SB_EXACT_JITTER_SAMPLES", std::to_string(jitterSamples_)});
  l.inputs = lists(false);
  opaque_.addTo(l);
  return l;
}

ExactShadow::Lists ExactShadow::readLists(Device& dev) {
  Lists l;
  l.stored = readBufferAs<uint32_t>(dev, cursor_);
  l.keys = readBufferAs<uint32_t>(dev, nodes_);
  l.keys.resize(complexity_.total * 2);
  return l;
}

std::vector<std::string> ExactShadow::warnings(Device& dev) {
  std::vector<std::string> w;
  if (method_ == Method::Peel && layers_ < complexity_.max)
    w.push_back("exact shadows: peeling capped at " + std::to_string(layers_) + " of " +
                std::to_string(complexity_.max) + " layers (option layers=)");
  if (method_ == Method::ABuffer) {
    const auto status = dev.readBuffer(status_);
    if (status[0] || status[1] || status[2] || status[3])
      w.push_back("exact shadows: light-space fragment list overflow");
  }
  return w;
}

}  // namespace sb
