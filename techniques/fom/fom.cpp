#include "techniques/fom/fom.h"

#include "render/common/opacity.h"
#include "render/common/shader_library.h"
#include "techniques/fom/slots.h"
#include "techniques/fom/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_FOM_PARAMS, kMaps = SB_SLOT_FOM_MAPS;
constexpr uint32_t kTargetsPerPass = 8;

}  // namespace

void FourierOpacityMaps::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  const ViewUniforms view = setupLight(dev, scene, s, opt_.size);
  // The series' period: the hair's depth range from the light (CPU, from the
  // hair points: exact for lines and ribbons), a little wider so that the
  // farthest fragment stays inside [0, 1).
  const DepthRange r = paddedHairDepthRange(dev, scene, view.viewProj);
  FomParams p{};
  p.fomViewProj = view.viewProj;
  p.fomParams = glm::vec4(opt_.bias, float(opt_.size), scene.shadowAlpha, 0.0f);
  p.fomRange = glm::vec4(r.nearZ, r.farZ, float(opt_.coefficients), 0.0f);
  params_ = dev.createBuffer({"fom.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);
  maps_ = dev.createTexture(
      {"fom.coefficients", Owner::Shadow, Format::RGBA32F, opt_.size, opt_.size, false, layers()});
  if (!scene.hasHair()) return;
  const ShaderCode vert = Geometry::strandVertexShader(s);
  for (uint32_t first = 0; first < layers(); first += kTargetsPerPass) {
    const uint32_t count = std::min(kTargetsPerPass, layers() - first);
    ShaderDefines defs;
    defs.defines = {{"SB_FOM_FIRST", std::to_string(first)},
                    {"SB_FOM_TARGETS", std::to_string(count)}};
    const ShaderCode frag = loadShader("techniques/fom/accumulate.frag", defs);
    PipelineDesc d =
        accumulatePass(first, count)
            .pipeline(dev, "fom.accumulate." + std::to_string(first / kTargetsPerPass), "fom");
    d.vertex = &vert;
    d.fragment = &frag;
    d.topology = Geometry::strandTopology(s);
    d.blend.assign(count, BlendState::additive());
    pipelines_.push_back(dev.createPipeline(d));
  }
}

// Layers first .. first + count - 1 of the coefficients, cleared, then every
// hair fragment added.
Pass FourierOpacityMaps::accumulatePass(uint32_t first, uint32_t count) const {
  Pass p(first == 0 ? "fom.accumulate"
                    : "fom.accumulate." + std::to_string(first / kTargetsPerPass));
  for (uint32_t t = 0; t < count; ++t) p.color(maps_, LoadOp::Clear, {0, 0, 0, 0}, first + t);
  return p.inputs(Geometry::inputs(*scene_, lightView_)).uniform(kParams, params_);
}

void FourierOpacityMaps::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  std::vector<Pass> passes;
  for (uint32_t first = 0; first < layers(); first += kTargetsPerPass)
    passes.push_back(accumulatePass(first, std::min(kTargetsPerPass, layers() - first)));
  // One node: the passes write disjoint layers of one texture.
  graph.add("fom.accumulate", passes, [this, &dev, vertices, passes] {
    for (std::size_t i = 0; i < passes.size(); ++i)
      passes[i].draw(dev, i < pipelines_.size() ? pipelines_[i] : Pipeline{}, vertices);
  });
}

ShadowLookup FourierOpacityMaps::lookup() const {
  ShadowLookup l{"techniques/fom/lookup.glsl"};
  l.inputs.uniform(kParams, params_).sampleArray(kMaps, maps_);
  opaque_.addTo(l);
  return l;
}

}  // namespace sb
