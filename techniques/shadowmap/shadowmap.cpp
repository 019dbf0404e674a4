#include "techniques/shadowmap/shadowmap.h"

#include "techniques/common/shader_library.h"

namespace sb {

namespace {
constexpr uint32_t kDepth = SB_SLOT_SHADOWMAP_DEPTH, kParams = SB_SLOT_SHADOWMAP_PARAMS;

struct Params {
  glm::mat4 lightViewProj;
  glm::vec4 params;
};
}  // namespace

void ShadowMap::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  scene_ = &scene;
  settings_ = s;
  depth_ = dev.createTexture({"shadowmap.depth", "shadow", Format::Depth32F, size_, size_, false});
  const ViewUniforms view = lightView(s, size_, size_);
  lightViewUbo_ = createLightViewBuffer(dev, view, "shadowmap");
  const Params p{view.viewProj, glm::vec4(bias_, 0, 0, 0)};
  paramsUbo_ = dev.createBuffer({"shadowmap.params", "frame", BufferUsage::Uniform, sizeof p}, &p);

  const ShaderCode frag = loadShader("techniques/common/depth_only.frag");
  PipelineDesc d;
  d.technique = "shadowmap";
  d.fragment = &frag;
  d.hasDepth = d.depthTest = d.depthWrite = true;
  d.depthCompare = CompareOp::Less;
  d.bindings = Geometry::slots();
  const auto pipelines = Geometry::pipelines(dev, d, scene, s, "shadowmap");
  hairPipeline_ = pipelines.hair;
  meshPipeline_ = pipelines.mesh;
}

void ShadowMap::addPasses(FrameGraph& graph, Device& dev) {
  // One pass: mesh and hair both occlude, so both go into the same depth map.
  graph.add({"shadowmap.depth", {}, {"shadow.depth"}, [this, &dev] {
               PassDesc pass;
               pass.name = "shadowmap.depth";
               pass.depth = {depth_, LoadOp::Clear, 1.0f};
               dev.beginPass(pass);
               const auto b = Geometry::bindings(*scene_, lightViewUbo_);
               if (meshPipeline_) dev.draw(meshPipeline_, b, scene_->meshTriangles * 3);
               if (hairPipeline_)
                 dev.draw(hairPipeline_, b, Geometry::strandVertexCount(*scene_, settings_));
               dev.endPass();
             }});
}

ShadowLookup ShadowMap::lookup() const {
  ShadowLookup l{"techniques/shadowmap/lookup.glsl"};
  l.read("shadow.depth").sample(kDepth, depth_).uniform(kParams, paramsUbo_);
  return l;
}

}  // namespace sb
