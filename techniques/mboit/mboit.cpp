#include "techniques/mboit/mboit.h"

#include <cmath>

#include "base/options.h"
#include "render/common/hair_oit.h"
#include "render/shading/hair_shading.h"
#include "techniques/mboit/mboit_math.h"
#include "techniques/mboit/slots.h"
#include "techniques/mboit/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_MBOIT_PARAMS, kB0 = SB_SLOT_MBOIT_B0, kLow = SB_SLOT_MBOIT_LOW,
                   kHigh = SB_SLOT_MBOIT_HIGH, kAccum = SB_SLOT_MBOIT_ACCUM;

// The view distances (along the camera's forward axis) that bound the scene:
// the log warp maps [near, far] onto [-1, 1].
glm::vec2 depthRange(const Bounds& b, const ViewUniforms& v) {
  float lo = 1e30f, hi = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 c((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                      (i & 4) ? b.max.z : b.min.z);
    const float z = glm::dot(c - glm::vec3(v.viewEye), glm::vec3(v.viewForward));
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  hi = std::max(hi, 1e-3f);
  lo = std::clamp(lo, hi * 1e-3f, hi * 0.999f);
  return {lo, hi};
}
}  // namespace

void MomentOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                      const HairShading& shading, const OitTargets& targets) {
  keep(scene, s, shading, targets);
  const glm::vec2 range = depthRange(scene.bounds, cameraView(s));
  const int kind = o_.trig ? SB_MBOIT_TRIG : SB_MBOIT_POWER;
  MboitParams p{{std::log(range.x), 1.0f / (std::log(range.y) - std::log(range.x)),
                 glsl::mboitKindBias(kind, o_.moments, o_.bits), SB_MBOIT_OVERESTIMATION},
                {o_.moments / 2, o_.bits, kind, 0}};
  params_ = dev.createBuffer({"mboit.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);
  const Format f = o_.bits == 16 ? Format::RGBA16F : Format::RGBA32F;
  b0_ = dev.createTexture({"mboit.b0", Owner::Oit, Format::R32F, s.width, s.height, false});
  low_ = dev.createTexture({"mboit.moments_1_4", Owner::Oit, f, s.width, s.height, false});
  if (highTarget())
    high_ = dev.createTexture({"mboit.moments_5_8", Owner::Oit, f, s.width, s.height, false});
  accum_ = dev.createTexture({"mboit.accum", Owner::Oit, f, s.width, s.height, false});

  ShaderDefines defs;
  if (highTarget()) defs.defines.push_back({"SB_MBOIT_HIGH", "1"});
  ShaderDefines shaded = defs;
  shaded.add(shading.hairDefines());
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode momentsFrag = loadShader("techniques/mboit/moments.frag", defs);
  const ShaderCode accumFrag = loadShader("techniques/mboit/accumulate.frag", shaded);

  // Both hair passes: depth-tested against the opaque depth without writing it,
  // additive into their targets.
  PipelineDesc d = transparentHairDesc(dev, momentsPass(), "mboit.moments", "mboit", vert, s);
  d.fragment = &momentsFrag;
  d.blend.assign(d.colorFormats.size(), BlendState::additive());
  moments_ = dev.createPipeline(d);

  PipelineDesc a = transparentHairDesc(dev, accumulatePass(), "mboit.accumulate",
                                       "mboit+" + shading.shadow().name(), vert, s);
  a.fragment = &accumFrag;
  a.blend = {BlendState::additive()};
  accumulate_ = dev.createPipeline(a);

  resolve_ = fullScreenPipeline(dev, resolvePass(), "mboit.resolve", "mboit",
                                "techniques/mboit/resolve.frag", {}, {hairOverBlend()});
}

// The first pass clears the depth when nothing opaque was drawn.
Pass MomentOit::momentsPass() const {
  Pass p("mboit.moments");
  p.color(b0_, LoadOp::Clear, {0, 0, 0, 0}).color(low_, LoadOp::Clear, {0, 0, 0, 0});
  if (highTarget()) p.color(high_, LoadOp::Clear, {0, 0, 0, 0});
  if (targets_.opaqueDrawn)
    p.depthReadOnly(targets_.depth);
  else
    p.depth(targets_.depth, LoadOp::Clear);
  return p.inputs(Geometry::inputs(*scene_, shading_->viewUbo())).uniform(kParams, params_);
}

Pass MomentOit::accumulatePass() const {
  Pass p("mboit.accumulate");
  p.color(accum_, LoadOp::Clear, {0, 0, 0, 0}).depthReadOnly(targets_.depth);
  p.inputs(shading_->hairInputs()).uniform(kParams, params_).sample(kB0, b0_).sample(kLow, low_);
  if (highTarget()) p.sample(kHigh, high_);
  return p;
}

Pass MomentOit::resolvePass() const {
  return Pass("mboit.resolve")
      .colorOver(targets_.color, targets_.opaqueDrawn, settings_.background)
      .sample(kB0, b0_)
      .sample(kAccum, accum_);
}

void MomentOit::addPasses(FrameGraph& graph, Device& dev) {
  const Pass moments = momentsPass(), accumulate = accumulatePass(), resolve = resolvePass();
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  graph.add("mboit", {moments, accumulate, resolve},
            [this, &dev, moments, accumulate, resolve, vertices] {
              moments.draw(dev, moments_, vertices);
              accumulate.draw(dev, accumulate_, vertices);
              resolve.draw(dev, resolve_, 3);
            });
}

}  // namespace sb
