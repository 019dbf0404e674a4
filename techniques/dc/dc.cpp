#include "techniques/dc/dc.h"

#include "scenes/options.h"
#include "techniques/common/shader_library.h"

namespace sb {

namespace {
// Binding numbers, as in techniques/dc/*.frag and lookup.glsl (15: OpaqueShadow).
constexpr uint32_t kParams = SB_SLOT_DC_PARAMS, kRange = SB_SLOT_DC_RANGE,
                   kCounts = SB_SLOT_DC_COUNTS, kSums = SB_SLOT_DC_SUMS,
                   kSquares = SB_SLOT_DC_SQUARES, kCentres = SB_SLOT_DC_CENTRES;

}  // namespace

DensityClusteringShadow::Options DensityClusteringShadow::readOptions(const OptionReader& o) {
  Options opts;
  opts.size = static_cast<uint32_t>(o.integer("size", 1, 16384));
  opts.bias = static_cast<float>(o.number("bias", 0.0, 1.0));
  opts.clusters = static_cast<uint32_t>(o.integer("clusters", 1, kMaxClusters));
  opts.iterations = static_cast<uint32_t>(o.integer("iterations", 1, 64));
  return opts;
}

ShadowLookup DensityClusteringShadow::lookup() const {
  ShadowLookup l{"techniques/dc/lookup.glsl"};
  l.defines.defines.push_back({"SB_DC_CLUSTERS", std::to_string(opts_.clusters)});
  l.defines.defines.push_back({"SB_DC_LAYERS", std::to_string(layers())});
  l.read("shadow.dc_range")
      .read("shadow.dc_clusters")
      .uniform(kParams, params_)
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
  params_ = createLightLookupParams(dev, view, opts_.bias, size, scene.shadowAlpha, "dc");
  auto map = [&](const std::string& what, Format f, uint32_t layers) {
    return dev.createTexture({"dc." + what, "shadow", f, size, size, false, layers});
  };
  range_ = map("depth_range", Format::RG32F, 1);
  centres_ = map("centres", Format::RGBA32F, layers());
  counts_ = map("counts", Format::RGBA32F, layers());
  sums_ = map("sums", Format::RGBA32F, layers());
  squares_ = map("square_sums", Format::RGBA32F, layers());
  opaque_.setup(dev, scene, size, lightView_, "dc");

  const ShaderDefines defs = lookupDefines();
  {  // The centres: a full-map triangle (also needed without hair: it clears).
    const ShaderCode vert = loadShader("techniques/common/composite.vert");
    PipelineDesc d;
    d.technique = "dc";
    d.vertex = &vert;
    d.colorFormats.assign(layers(), Format::RGBA32F);
    d.bindings = {{kRange, BindingKind::SampledTexture}};
    for (int first = 1; first >= 0; --first) {
      ShaderDefines md = defs;
      md.defines.push_back({"SB_DC_FIRST", std::to_string(first)});
      const ShaderCode frag = loadShader("techniques/dc/means.frag", md);
      d.name = first ? "dc.means.first" : "dc.means";
      d.fragment = &frag;
      if (!first) {
        d.bindings.push_back({kCounts, BindingKind::SampledTextureArray});
        d.bindings.push_back({kSums, BindingKind::SampledTextureArray});
      }
      (first ? firstMeansPipeline_ : meansPipeline_) = dev.createPipeline(d);
    }
  }
  if (!scene.hasHair()) return;

  const ShaderCode vert = Geometry::strandVertexShader(s);
  PipelineDesc d;
  d.technique = "dc";
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  d.bindings = Geometry::slots();
  const ShaderCode rangeFrag = loadShader("techniques/common/depth_range.frag", defs);
  d.name = "dc.init";
  d.fragment = &rangeFrag;
  d.colorFormats = {Format::RG32F};
  d.blend = {BlendState::min()};
  rangePipeline_ = dev.createPipeline(d);

  const ShaderCode iterateFrag = loadShader("techniques/dc/iterate.frag", defs);
  d.name = "dc.iterate";
  d.fragment = &iterateFrag;
  d.bindings.push_back({kRange, BindingKind::SampledTexture});
  d.bindings.push_back({kCentres, BindingKind::SampledTextureArray});
  d.colorFormats.assign(3 * layers(), Format::RGBA32F);
  d.blend.assign(3 * layers(), BlendState::additive());
  iteratePipeline_ = dev.createPipeline(d);
}

void DensityClusteringShadow::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  graph.add({"dc.init", {}, {"shadow.dc_range"}, [this, &dev] {
               PassDesc pass;
               pass.name = "dc.init";
               ColorAttachment a;
               a.texture = range_;
               a.clear = {2.0f, 2.0f, 0.0f, 0.0f};  // nearest 2, furthest -2: empty
               pass.color = {a};
               dev.beginPass(pass);
               if (rangePipeline_)
                 dev.draw(rangePipeline_, Geometry::bindings(*scene_, lightView_),
                          Geometry::strandVertexCount(*scene_, settings_));
               dev.endPass();
             }});
  // k-means: centres, then every fragment joins its nearest centre's sums.
  graph.add({"dc.iterate", {"shadow.dc_range"}, {"shadow.dc_clusters"}, [this, &dev] {
               for (uint32_t i = 0; i < opts_.iterations; ++i) {
                 PassDesc means;
                 means.name = "dc.means";
                 for (uint32_t l = 0; l < layers(); ++l)
                   means.color.push_back({centres_, LoadOp::Clear, {}, {}, l});
                 means.sampledTextures = {range_};
                 std::vector<Binding> mb = {Binding::tex(kRange, range_)};
                 if (i > 0) {
                   means.sampledTextures.push_back(counts_);
                   means.sampledTextures.push_back(sums_);
                   mb.push_back(Binding::tex(kCounts, counts_));
                   mb.push_back(Binding::tex(kSums, sums_));
                 }
                 dev.beginPass(means);
                 dev.draw(i == 0 ? firstMeansPipeline_ : meansPipeline_, mb, 3);
                 dev.endPass();

                 PassDesc iterate;
                 iterate.name = "dc.iterate";
                 for (Texture t : {counts_, sums_, squares_})
                   for (uint32_t l = 0; l < layers(); ++l)
                     iterate.color.push_back({t, LoadOp::Clear, {}, {}, l});
                 iterate.sampledTextures = {range_, centres_};
                 dev.beginPass(iterate);
                 if (iteratePipeline_) {
                   auto b = Geometry::bindings(*scene_, lightView_);
                   b.push_back(Binding::tex(kRange, range_));
                   b.push_back(Binding::tex(kCentres, centres_));
                   dev.draw(iteratePipeline_, b, Geometry::strandVertexCount(*scene_, settings_));
                 }
                 dev.endPass();
               }
             }});
}

}  // namespace sb
