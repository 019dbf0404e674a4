#include "techniques/msm/msm.h"

#include "render/common/opacity.h"
#include "render/common/shader_library.h"
#include "techniques/mboit/mboit_math.h"
#include "techniques/msm/slots.h"
#include "techniques/msm/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_MSM_PARAMS, kB0 = SB_SLOT_MSM_B0, kLow = SB_SLOT_MSM_LOW,
                   kHigh = SB_SLOT_MSM_HIGH;

int kind(const MomentShadowMaps::Options& o) { return o.trig ? SB_MBOIT_TRIG : SB_MBOIT_POWER; }
}  // namespace

void MomentShadowMaps::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  const ViewUniforms view = setupLight(dev, scene, s, opt_.size);
  // The moments' depth interval: the hair's depth range from the light (as
  // fom's series period), a little wider so that no fragment sits on its end.
  const DepthRange r = paddedHairDepthRange(dev, scene, view.viewProj);
  MsmParams p{};
  p.msmViewProj = view.viewProj;
  p.msmParams = glm::vec4(opt_.bias, float(opt_.size), scene.shadowAlpha,
                          glsl::mboitKindBias(kind(opt_), opt_.moments, 32));
  p.msmRange = glm::vec4(r.nearZ, r.farZ, SB_MBOIT_OVERESTIMATION, 0.0f);
  p.msmN = glm::ivec4(opt_.moments, kind(opt_), 0, 0);
  params_ = dev.createBuffer({"msm.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);
  b0_ = dev.createTexture({"msm.b0", Owner::Shadow, Format::R32F, opt_.size, opt_.size, false});
  low_ = dev.createTexture(
      {"msm.moments_1_4", Owner::Shadow, Format::RGBA32F, opt_.size, opt_.size, false});
  if (highTarget())
    high_ = dev.createTexture(
        {"msm.moments_5_8", Owner::Shadow, Format::RGBA32F, opt_.size, opt_.size, false});
  if (!scene.hasHair()) return;
  ShaderDefines defs;
  if (highTarget()) defs.defines.push_back({"SB_MSM_HIGH", "1"});
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode frag = loadShader("techniques/msm/accumulate.frag", defs);
  PipelineDesc d = accumulatePass().pipeline(dev, "msm.accumulate", "msm");
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(s);
  d.blend.assign(d.colorFormats.size(), BlendState::additive());
  pipeline_ = dev.createPipeline(d);
}

// The moment targets, cleared, then every hair fragment added.
Pass MomentShadowMaps::accumulatePass() const {
  Pass p("msm.accumulate");
  p.color(b0_, LoadOp::Clear, {0, 0, 0, 0}).color(low_, LoadOp::Clear, {0, 0, 0, 0});
  if (highTarget()) p.color(high_, LoadOp::Clear, {0, 0, 0, 0});
  return p.inputs(Geometry::inputs(*scene_, lightView_)).uniform(kParams, params_);
}

void MomentShadowMaps::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  const Pass pass = accumulatePass();
  graph.add("msm.accumulate", {pass},
            [this, &dev, vertices, pass] { pass.draw(dev, pipeline_, vertices); });
}

ShadowLookup MomentShadowMaps::lookup() const {
  ShadowLookup l{"techniques/msm/lookup.glsl"};
  if (highTarget()) l.defines.defines.push_back({"SB_MSM_HIGH", "1"});
  l.inputs.uniform(kParams, params_).sample(kB0, b0_).sample(kLow, low_);
  if (highTarget()) l.inputs.sample(kHigh, high_);
  opaque_.addTo(l);
  return l;
}

// The configuration the numbers depend on: real moments beyond b0, their
// kind and the paper's bias used.
std::vector<Counter> MomentShadowMaps::counters(Device& /*dev*/) {
  return {{"moments", double(opt_.moments)},
          {"trigonometric", opt_.trig ? 1.0 : 0.0},
          {"moment_bias", double(glsl::mboitKindBias(kind(opt_), opt_.moments, 32))}};
}

}  // namespace sb
