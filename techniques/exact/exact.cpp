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
constexpr uint32_t kPageSlots[] = {kNodes, SB_SLOT_EXACT_PAGE1, SB_SLOT_EXACT_PAGE2};
constexpr std::size_t kNodeBytes = 8;                  // uvec2: (depth bits, primitive id)
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
  // One more than the texels: the total, where the last list ends (the lookup).
  offsets_ =
      dev.createBuffer({"exact.offsets", Owner::Shadow, BufferUsage::Storage, (texels + 1) * 4});
  cursor_ = dev.createBuffer({"exact.cursor", Owner::Shadow, BufferUsage::Storage, texels * 4});
  status_ = dev.createBuffer({"exact.status", Owner::Shadow, BufferUsage::Storage, 16});
  // Sized by prepare()'s count; declared now so that the frame graph is built
  // (and culled) before any preparation runs.
  static_assert(std::size(kPageSlots) == kPages);
  pageShift_ = poolPageShift(dev.info(), kNodeBytes);
  nodes_.resize(kPages);
  for (uint32_t page = 0; page < kPages; ++page)
    nodes_[page] =
        dev.createBuffer({"exact.nodes" + (page ? ".page" + std::to_string(page) : std::string()),
                          Owner::Shadow, BufferUsage::Storage, kNodeBytes});
  if (method_ == Method::Peel)
    state_ =
        dev.createBuffer({"exact.peel_state", Owner::Shadow, BufferUsage::Storage, texels * 16});
  else
    state_ = dev.createBuffer({"exact.peel_state", Owner::Shadow, BufferUsage::Storage, 16});
  opaque_.setup(dev, scene, size_, lightView_, "exact");

  count_ = makeHairCountPipeline(dev, s, countPass(), kCounts, "exact");
  makeListPipelines(dev);
  if (method_ == Method::Peel)
    advance_ =
        makePeelAdvancePipeline(dev, advancePass(), kState, kCursor, kOffsets, kNodes, "exact");
}

ShaderDefines ExactShadow::pageDefines(uint32_t pages) const {
  ShaderDefines d;
  d.defines = {{"SB_EXACT_PAGES", std::to_string(pages)},
               {"SB_EXACT_PAGE_SHIFT", std::to_string(pageShift_)}};
  return d;
}

// The light passes that write the lists, compiled for the pages the pool uses
// (nodes.glsl).
void ExactShadow::makeListPipelines(Device& dev) {
  const ShaderCode vert = Geometry::strandVertexShader(settings_);
  PipelineDesc d = listPass("exact.fill").pipeline(dev, "exact.fill", "exact");
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(settings_);
  const ShaderDefines pool = pageDefines(pagesUsed_);
  if (method_ == Method::ABuffer) {
    dev.destroy(fill_);
    dev.destroy(sort_);
    const ShaderCode frag = loadShader("techniques/exact/fill.frag", pool);
    d.fragment = &frag;
    fill_ = dev.createPipeline(d);
    ShaderDefines order = pool;
    if (bySubmission_) order.defines.push_back({"SB_EXACT_BY_SUBMISSION", "1"});
    const ShaderCode comp = loadShader("techniques/exact/sort.comp", order);
    PipelineDesc c = sortPass().pipeline(dev, "exact.sort", "exact");
    c.compute = &comp;
    sort_ = dev.createPipeline(c);
    return;
  }
  for (int pass = 0; pass < 2; ++pass) {
    ShaderDefines defs = pool;
    defs.defines.push_back({"SB_PEEL_PASS", std::to_string(pass)});
    const ShaderCode frag = loadShader("techniques/exact/peel.frag", defs);
    d.name = pass == 0 ? "exact.peel.depth" : "exact.peel.id";
    d.fragment = &frag;
    (pass == 0 ? peel0_ : peel1_) = dev.createPipeline(d);
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
  std::vector<uint32_t> offsets = layout.offsets;
  offsets.push_back(static_cast<uint32_t>(layout.complexity.total));
  dev.updateBuffer(offsets_, offsets.data(), offsets.size() * 4);
  // The pool in pages that each fit one storage binding; peeling stores each
  // layer through the shared peel_advance.comp, which binds one.
  const std::vector<Buffer> bound(nodes_.begin(),
                                  method_ == Method::Peel ? nodes_.begin() + 1 : nodes_.end());
  const uint32_t pages = sizePoolPages(
      dev, bound, layout.complexity.total, pageShift_, kNodeBytes, "exact: the node pool",
      method_ == Method::Peel
          ? "use method=abuffer, which pages it, or a smaller light map (size=)"
          : "use a smaller --size, light map (size=) or samples=, or fewer strands");
  if (pages != pagesUsed_) {
    pagesUsed_ = pages;
    makeListPipelines(dev);
  }
  layers_ = std::min(complexity_.max, maxLayers_);
}

// The fragment lists and their parameters: every pass of the technique binds
// them all (and writes them); the lookup reads them.
Inputs ExactShadow::lists() const {
  Inputs in;
  in.uniform(kParams, params_)
      .storage(kCounts, counts_)
      .storage(kOffsets, offsets_)
      .storage(kCursor, cursor_)
      .storage(kState, state_)
      .storage(kStatus, status_);
  return in.add(pages(true));
}

// Every page of the node pool, the unused ones too (8 bytes).
Inputs ExactShadow::pages(bool written) const {
  Inputs in;
  for (uint32_t page = 0; page < kPages; ++page)
    written ? in.storage(kPageSlots[page], nodes_[page])
            : in.readStorage(kPageSlots[page], nodes_[page]);
  return in;
}

Inputs ExactShadow::sortedLists() const {
  Inputs in;
  in.readStorage(kCounts, counts_).readStorage(kOffsets, offsets_).readStorage(kCursor, cursor_);
  return in.add(pages(false));
}

// A hair pass from the light into the lists (no attachments: the light map's size).
Pass ExactShadow::listPass(const std::string& name) const {
  return Pass(name)
      .size(size_, size_)
      .inputs(Geometry::inputs(*scene_, lightView_))
      .inputs(lists());
}

Pass ExactShadow::countPass() const {
  return Pass("exact.count")
      .size(size_, size_)
      .inputs(Geometry::inputs(*scene_, lightView_))
      .storage(kCounts, counts_);
}

Pass ExactShadow::sortPass() const { return Pass("exact.sort").inputs(lists()); }

Pass ExactShadow::advancePass() const {
  return Pass("exact.peel.advance")
      .uniform(kSize, sizeUbo_)
      .storage(kState, state_)
      .storage(kCursor, cursor_)
      .storage(kOffsets, offsets_)
      .storage(kNodes, nodes_[0]);
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
  // Only what it reads: cursor, state and status sit in the transparency's slots.
  ShadowLookup l{"techniques/exact/lookup.glsl"};
  l.defines = readerDefines();
  l.defines.defines.push_back({"SB_EXACT_JITTER_SAMPLES", std::to_string(jitterSamples_)});
  l.inputs.uniform(kParams, params_).readStorage(kOffsets, offsets_);
  l.inputs.add(pages(false));
  opaque_.addTo(l);
  return l;
}

ExactShadow::Lists ExactShadow::readLists(Device& dev) {
  Lists l;
  l.stored = readBufferAs<uint32_t>(dev, cursor_);
  for (uint32_t page = 0; page < pagesUsed_; ++page) {
    const auto keys = readBufferAs<uint32_t>(dev, nodes_[page]);
    l.keys.insert(l.keys.end(), keys.begin(), keys.end());
  }
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
