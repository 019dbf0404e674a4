#include <glm/gtc/matrix_transform.hpp>

#include "render/common/shader_library.h"
#include "render/common/technique.h"
#include "render/generation/groom_table.h"

namespace sb {

ViewUniforms cameraView(const RenderSettings& s) {
  const float aspect = static_cast<float>(s.width) / static_cast<float>(s.height);
  ViewUniforms v{};
  v.viewProj = s.camera.projection(aspect) * s.camera.view();
  v.viewEye = glm::vec4(s.camera.eye, 1.0f);
  v.viewForward = glm::vec4(glm::normalize(s.camera.target - s.camera.eye), 0.0f);
  v.viewViewport = glm::vec4(static_cast<float>(s.width), static_cast<float>(s.height),
                             s.ribbonWidth, s.worldThickness);
  return v;
}

ViewUniforms lightView(const RenderSettings& s, uint32_t mapWidth, uint32_t mapHeight) {
  ViewUniforms v{};
  v.viewProj = s.light.projection() * s.light.view();
  const bool point = s.light.type == LightType::Point;
  v.viewEye = glm::vec4(s.light.position, point ? 1.0f : 0.0f);
  v.viewForward = glm::vec4(glm::normalize(s.light.direction), 0.0f);
  v.viewViewport = glm::vec4(static_cast<float>(mapWidth), static_cast<float>(mapHeight),
                             s.ribbonWidth, s.worldThickness);
  return v;
}

Buffer createLightViewBuffer(Device& dev, const ViewUniforms& view, const std::string& technique) {
  return dev.createBuffer(
      {technique + ".light_view", Owner::Frame, BufferUsage::Uniform, sizeof view}, &view);
}

ShaderCode Geometry::strandVertexShader(const RenderSettings& s) {
  ShaderDefines d;
  if (s.primitive != Primitive::Lines) d.defines.push_back({"SB_RIBBONS", "1"});
  if (s.primitive == Primitive::World) d.defines.push_back({"SB_WORLD", "1"});
  if (s.geometry != GeometryPath::Mesh) return loadShader("render/common/strands.vert", d);
  // The mesh path: a mesh shader in the vertex shader's place, drawing the same
  // vertices (ShaderCode::meshGroupVertices) from the groom.
  ShaderCode mesh = loadShader("render/generation/strands.mesh", d);
  mesh.meshGroupVertices = SB_MESH_SEGMENTS * (s.primitive == Primitive::Lines ? 2u : 6u);
  return mesh;
}

ShaderCode Geometry::meshVertexShader() { return loadShader("render/common/mesh.vert"); }

Topology Geometry::strandTopology(const RenderSettings& s) {
  return s.primitive == Primitive::Lines ? Topology::Lines : Topology::Triangles;
}

uint32_t Geometry::strandVertexCount(const GpuScene& g, const RenderSettings& s) {
  return g.segmentCount * (s.primitive == Primitive::Lines ? 2u : 6u);
}

Inputs Geometry::inputs(const GpuScene& g, Buffer viewUbo) {
  Inputs in;
  in.uniform(bind::kView, viewUbo)
      .readStorage(bind::kPoints, g.points)
      .readStorage(bind::kColors, g.colors)
      .readStorage(bind::kSegments, g.segments)
      .readStorage(bind::kMeshPositions, g.meshPositions)
      .readStorage(bind::kMeshNormals, g.meshNormals)
      .readStorage(bind::kMeshIndices, g.meshIndices);
  return in;
}

Geometry::HairAndMesh Geometry::pipelines(Device& dev, PipelineDesc d, const GpuScene& g,
                                          const RenderSettings& s, const std::string& name) {
  HairAndMesh out;
  if (g.hasHair()) {
    const ShaderCode vert = strandVertexShader(s);
    d.name = name + ".hair";
    d.vertex = &vert;
    d.topology = strandTopology(s);
    out.hair = dev.createPipeline(d);
  }
  if (g.hasMesh()) {
    const ShaderCode vert = meshVertexShader();
    d.name = name + ".mesh";
    d.vertex = &vert;
    d.topology = Topology::Triangles;
    out.mesh = dev.createPipeline(d);
  }
  return out;
}

}  // namespace sb
