#include "techniques/dc/dc.h"

#include "base/options.h"
#include "render/common/shader_library.h"
#include "techniques/dc/slots.h"
#include "techniques/dc/uniforms.h"

namespace sb {

namespace {
// Binding numbers, as in techniques/dc/*.frag and lookup.glsl (15: OpaqueShadow).
constexpr uint32_t kParams = SB_SLOT_DC_PARAMS, kRange = SB_SLOT_DC_RANGE,
                   kCounts = SB_SLOT_DC_COUNTS, kSums = SB_SLOT_DC_SUMS,
                   kSquares = SB_SLOT_DC_SQUARES, kCentres = SB_SLOT_DC_CENTRES;

}  // namespace

ShadowLookup DensityClusteringShadow::lookup() const {
  ShadowLookup l{"techniques/dc/lookup.glsl"};
  l.defines.defines.push_back({"SB_DC_CLUSTERS", std::to_string(opts_.clusters)});
  l.defines.defines.push_back({"SB_DC_LAYERS", std::to_string(layers())});
  // The passes place fragments by light distance (light_pass_depth.glsl).
  l.defines.defines.push_back({"SB_LIGHT_DISTANCE", "1"});
  l.inputs.uniform(kParams, params_)
      .sample(kRange, range_)
      .sampleArray(kCounts, counts_)
      .sampleArray(kSums, sums_)
      .sampleArray(kSquares, squares_);
  opaque_.addTo(l);
  return l;
}

void DensityClusteringShadow::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  scene_ = &scene;
  settings_ = s;
  const uint32_t size = opts_.size;
  const ViewUniforms view = lightView(s, size, size);
  lightView_ = createLightViewBuffer(dev, view, "dc");
  params_ = createLightLookupParams<DcParams>(dev, view, opts_.bias, size, scene.shadowAlpha, "dc");
  auto map = [&](const std::string& what, Format f, uint32_t layers) {
    return dev.createTexture({"dc." + what, Owner::Shadow, f, size, size, false, layers});
  };
  range_ = map("depth_range", Format::RG32F, 1);
  centres_ = map("centres", Format::RGBA32F, layers());
  counts_ = map("counts", Format::RGBA32F, layers());
  sums_ = map("sums", Format::RGBA32F, layers());
  squares_ = map("square_sums", Format::RGBA32F, layers());
  opaque_.setup(dev, scene, size, lightView_, "dc");

  const ShaderDefines defs = lookup().defines;
  {  // The centres: a full-map triangle (also needed without hair: it clears).
    const ShaderCode vert = loadShader("render/common/composite.vert");
    for (int first = 1; first >= 0; --first) {
      ShaderDefines md = defs;
      md.defines.push_back({"SB_DC_FIRST", std::to_string(first)});
      const ShaderCode frag = loadShader("techniques/dc/means.frag", md);
      PipelineDesc d = meansPass(first).pipeline(dev, first ? "dc.means.first" : "dc.means", "dc");
      d.vertex = &vert;
      d.fragment = &frag;
      (first ? firstMeansPipeline_ : meansPipeline_) = dev.createPipeline(d);
    }
  }
  if (!scene.hasHair()) return;

  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode rangeFrag = loadShader("render/common/depth_range.frag", defs);
  PipelineDesc d = initPass().pipeline(dev, "dc.init", "dc");
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  d.fragment = &rangeFrag;
  d.blend = {BlendState::min()};
  rangePipeline_ = dev.createPipeline(d);

  const ShaderCode iterateFrag = loadShader("techniques/dc/iterate.frag", defs);
  PipelineDesc it = iteratePass().pipeline(dev, "dc.iterate", "dc");
  it.vertex = &vert;
  it.topology = Geometry::strandTopology(s);
  it.fragment = &iterateFrag;
  it.blend.assign(3 * layers(), BlendState::additive());
  iteratePipeline_ = dev.createPipeline(it);
}

// The hair's depth range per texel (min blending of near and -far).
Pass DensityClusteringShadow::initPass() const {
  return Pass("dc.init")
      .color(range_, LoadOp::Clear, {2.0f, 2.0f, 0.0f, 0.0f})  // nearest 2, furthest -2: empty
      .inputs(Geometry::inputs(*scene_, lightView_));
}

// The cluster centres: spread over the range at first, then the means of the
// previous iteration's clusters.
Pass DensityClusteringShadow::meansPass(bool first) const {
  Pass p("dc.means");
  for (uint32_t l = 0; l < layers(); ++l) p.color(centres_, LoadOp::Clear, {}, l);
  p.sample(kRange, range_);
  if (!first) p.sampleArray(kCounts, counts_).sampleArray(kSums, sums_);
  return p;
}

// Every fragment joins its nearest centre's count, sum and sum of squares.
Pass DensityClusteringShadow::iteratePass() const {
  Pass p("dc.iterate");
  for (Texture t : {counts_, sums_, squares_})
    for (uint32_t l = 0; l < layers(); ++l) p.color(t, LoadOp::Clear, {}, l);
  return p.inputs(Geometry::inputs(*scene_, lightView_))
      .sample(kRange, range_)
      .sampleArray(kCentres, centres_);
}

void DensityClusteringShadow::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  graph.add(initPass(),
            [this, &dev, vertices, p = initPass()] { p.draw(dev, rangePipeline_, vertices); });
  // k-means: centres, then every fragment joins its nearest centre's sums.
  const Pass first = meansPass(true), means = meansPass(false), iterate = iteratePass();
  graph.add("dc.iterate", {first, iterate, means}, [this, &dev, vertices, first, means, iterate] {
    for (uint32_t i = 0; i < opts_.iterations; ++i) {
      if (i == 0)
        first.draw(dev, firstMeansPipeline_, 3);
      else
        means.draw(dev, meansPipeline_, 3);
      iterate.draw(dev, iteratePipeline_, vertices);
    }
  });
}

}  // namespace sb
