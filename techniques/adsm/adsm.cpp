#include "techniques/adsm/adsm.h"

#include <cmath>
#include <cstring>

#include "render/common/shader_library.h"
#include "techniques/adsm/slots.h"
#include "techniques/adsm/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_ADSM_PARAMS, kDepth = SB_SLOT_ADSM_DEPTH;

// Half the mean strand thickness (vec4 w of the points), read back once.
float meanRadius(Device& dev, const GpuScene& scene) {
  if (!scene.hasHair()) return 0.0f;
  const std::vector<uint8_t> bytes = dev.readBuffer(scene.points);
  const std::size_t n = bytes.size() / sizeof(glm::vec4);
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    glm::vec4 p;
    std::memcpy(&p, bytes.data() + i * sizeof p, sizeof p);
    sum += p.w;
  }
  return n ? float(0.5 * sum / double(n)) : 0.0f;
}
}  // namespace

void ApproximatedDeepShadows::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  const ViewUniforms view = setupLight(dev, scene, s, opt_.size);
  // Light depth is linear in distance for the directional light's orthographic
  // projection: one depth unit is 1 / |d ndc.z / d world| world units (the
  // z row of the view-projection); for a point light an approximation.
  const glm::vec3 zRow(view.viewProj[0][2], view.viewProj[1][2], view.viewProj[2][2]);
  worldPerDepth_ = 1.0f / std::max(glm::length(zRow), 1e-12f);
  radius_ = meanRadius(dev, scene);
  AdsmParams p{};
  p.adsmViewProj = view.viewProj;
  p.adsmParams = glm::vec4(opt_.bias, float(opt_.size), scene.shadowAlpha, 0.0f);
  p.adsmFiber = glm::vec4(worldPerDepth_, opt_.spacing * radius_, float(opt_.kernel), 0.0f);
  params_ = dev.createBuffer({"adsm.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);
  depth_ = dev.createTexture(
      {"adsm.depth", Owner::Shadow, Format::Depth32F, opt_.size, opt_.size, false});
  if (!scene.hasHair()) return;
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode frag = loadShader("render/common/depth_only.frag");
  PipelineDesc d = depthPass().pipeline(dev, "adsm.depth", "adsm");
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(s);
  d.depthCompare = CompareOp::Less;
  pipeline_ = dev.createPipeline(d);
}

// The hair's front from the light: a depth-only pass.
Pass ApproximatedDeepShadows::depthPass() const {
  return Pass("adsm.depth")
      .depth(depth_, LoadOp::Clear)
      .inputs(Geometry::inputs(*scene_, lightView_));
}

void ApproximatedDeepShadows::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  graph.add(depthPass(),
            [this, &dev, vertices, p = depthPass()] { p.draw(dev, pipeline_, vertices); });
}

ShadowLookup ApproximatedDeepShadows::lookup() const {
  ShadowLookup l{"techniques/adsm/lookup.glsl"};
  l.inputs.uniform(kParams, params_).sample(kDepth, depth_);
  opaque_.addTo(l);
  return l;
}

std::vector<Counter> ApproximatedDeepShadows::counters(Device& /*dev*/) {
  return {{"adsm_fiber_radius", double(radius_)},
          {"adsm_fiber_depth", double(opt_.spacing * radius_)},
          {"adsm_world_per_depth", double(worldPerDepth_)}};
}

}  // namespace sb
