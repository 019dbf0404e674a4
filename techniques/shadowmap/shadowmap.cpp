#include "techniques/shadowmap/shadowmap.h"

#include "render/common/shader_library.h"
#include "techniques/shadowmap/slots.h"
#include "techniques/shadowmap/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kDepth = SB_SLOT_SHADOWMAP_DEPTH, kParams = SB_SLOT_SHADOWMAP_PARAMS;
}  // namespace

void ShadowMap::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  scene_ = &scene;
  settings_ = s;
  depth_ =
      dev.createTexture({"shadowmap.depth", Owner::Shadow, Format::Depth32F, size_, size_, false});
  const ViewUniforms view = lightView(s, size_, size_);
  lightViewUbo_ = createLightViewBuffer(dev, view, "shadowmap");
  const ShadowMapParams p{view.viewProj, glm::vec4(bias_, 0, 0, 0)};
  paramsUbo_ =
      dev.createBuffer({"shadowmap.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);

  const ShaderCode frag = loadShader("render/common/depth_only.frag");
  PipelineDesc d = pass().pipeline(dev, "shadowmap.depth", "shadowmap");
  d.fragment = &frag;
  d.depthCompare = CompareOp::Less;
  const auto pipelines = Geometry::pipelines(dev, d, scene, s, "shadowmap");
  hairPipeline_ = pipelines.hair;
  meshPipeline_ = pipelines.mesh;
}

// One pass: mesh and hair both occlude, so both go into the same depth map.
Pass ShadowMap::pass() const {
  return Pass("shadowmap.depth")
      .depth(depth_, LoadOp::Clear)
      .inputs(Geometry::inputs(*scene_, lightViewUbo_));
}

void ShadowMap::addPasses(FrameGraph& graph, Device& dev) {
  graph.add(pass(), [this, &dev, p = pass()] {
    p.draw(dev, {{meshPipeline_, scene_->meshTriangles * 3},
                 {hairPipeline_, Geometry::strandVertexCount(*scene_, settings_)}});
  });
}

ShadowLookup ShadowMap::lookup() const {
  ShadowLookup l{"techniques/shadowmap/lookup.glsl"};
  l.inputs.sample(kDepth, depth_).uniform(kParams, paramsUbo_);
  return l;
}

}  // namespace sb
