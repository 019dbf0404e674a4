#include "techniques/opaque_hair/opaque_hair.h"

#include "techniques/common/shader_library.h"
#include "techniques/kajiya_kay/shading.h"

namespace sb {

void OpaqueHair::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                       const KajiyaKayShading& shading, const OitTargets& targets) {
  scene_ = &scene;
  shading_ = &shading;
  settings_ = s;
  targets_ = targets;
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode frag = loadShader("techniques/kajiya_kay/hair.frag", shading.hairDefines());
  PipelineDesc d;
  d.name = "shading.hair";
  d.technique = "kajiya_kay+" + shading.shadow().name();
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(s);
  d.colorFormats = {Format::RGBA32F};
  d.hasDepth = d.depthTest = d.depthWrite = true;
  d.depthCompare = CompareOp::Less;
  d.bindings = shading.hairSlots();
  pipeline_ = dev.createPipeline(d);
}

void OpaqueHair::addPasses(FrameGraph& graph, Device& dev) {
  auto reads = shading_->shadowReads();
  if (targets_.opaqueDrawn) {
    reads.push_back("color");
    reads.push_back("depth");
  }
  graph.add({"shading.hair", reads, {"color", "depth"}, [this, &dev] {
               const LoadOp load = targets_.opaqueDrawn ? LoadOp::Load : LoadOp::Clear;
               PassDesc pass;
               pass.name = "shading.hair";
               const glm::vec3 bg = settings_.background;
               pass.color = {{targets_.color, load, {bg.r, bg.g, bg.b, 1.0f}}};
               pass.depth = {targets_.depth, load, 1.0f};
               pass.sampledTextures = shading_->sampledTextures();
               dev.beginPass(pass);
               dev.draw(pipeline_, shading_->hairBindings(),
                        Geometry::strandVertexCount(*scene_, settings_));
               dev.endPass();
             }});
}

}  // namespace sb
