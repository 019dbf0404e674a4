// What every technique sees: the scene on the GPU, the render settings, and
// the interface a shadow technique implements. Techniques never name GL or
// Vulkan; they create resources and record passes through Device.
#pragma once

#include <algorithm>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backends/device.h"
#include "render/common/shader_library.h"
#include "render/common/slots.h"
#include "render/common/view_uniforms.h"
#include "render/graph/frame_graph.h"
#include "render/graph/pass.h"
#include "render/shading/shading_model.h"
#include "scenes/scene.h"
#include "scenes/view.h"

namespace sb {

// World: ribbons of the strands' world width, at least a pixel, alpha times coverage.
enum class Primitive { Lines, Ribbons, World };
// Where the strands are made (render --geometry, docs/geometry.md): expanded on the
// CPU and uploaded, made from the scene's groom by a compute pass on the device,
// or made from it in mesh shaders as they are drawn (Geometry::strandVertexShader).
enum class GeometryPath { Cpu, Compute, Mesh };

struct RenderSettings {
  ShadingModel shading;  // hair shading model of the final passes
  uint32_t width = 512, height = 512;
  Primitive primitive = Primitive::Lines;
  GeometryPath geometry = GeometryPath::Cpu;
  float ribbonWidth = 1.0f;  // pixels of the target being drawn
  // World: the thickness (world units) of a strand point that has none.
  float worldThickness = 0.0f;
  // Samples per pixel of the frame's colour and depth (--msaa): 1, or a count
  // the device supports; only techniques that are multisampled() take more.
  uint32_t msaa = 1;
  Camera camera;
  Light light;  // the key light: its shadows are the visibility and probe outputs
  // Lights 2, 3, ...: each gets its own instance of the shadow technique and
  // its own shading; the frame's colour is the sum over lights
  // (render/frame/renderer.h). Ambient light and the background count once.
  std::vector<Light> extraLights;
  bool ambient = true;  // false in the shading of an extra light
  glm::vec3 background{0.0f, 0.0f, 0.0f};
  std::vector<glm::vec3> probePoints;  // world points for the "probe" output
};

// The scene's data on the device (owner "scene").
struct GpuScene {
  Buffer points;    // vec4: xyz, thickness
  Buffer colors;    // vec4: rgb, alpha
  Buffer segments;  // uint: index of a segment's first point
  uint32_t segmentCount = 0;
  Buffer meshPositions;  // vec4
  Buffer meshNormals;    // vec4
  Buffer meshIndices;    // uint, 3 per triangle
  uint32_t meshTriangles = 0;
  float hairAlpha = 1.0f;
  float shadowAlpha = 0.5f;
  Bounds bounds;
  // The drawn strands' points on the host, while the renderer sets its techniques up,
  // where the device holds none (--geometry mesh: only the groom; these are the points
  // its mesh shader makes). Null otherwise: scene.points is read back. Null after setup.
  const std::vector<glm::vec3>* hostPoints = nullptr;
  bool hasHair() const { return segmentCount > 0; }
  bool hasMesh() const { return meshTriangles > 0; }
};

struct DepthComplexity {
  uint32_t max = 0;
  double mean = 0;  // over pixels with at least one fragment
  uint64_t total = 0;
  // Fragments per pixel, rows bottom-up (row 0 = NDC y=-1): the error per
  // bucket of layers in reports.
  std::vector<uint32_t> counts;
};

// A view's uniforms (binding 0 in every geometry pass): ViewUniforms, declared in
// render/common/view_uniforms.h.
ViewUniforms cameraView(const RenderSettings& s);
ViewUniforms lightView(const RenderSettings& s, uint32_t mapWidth, uint32_t mapHeight);
// A shadow technique's light view as the uniform buffer "<technique>.light_view"
// (owner "frame"), bound at binding 0 of its light passes.
Buffer createLightViewBuffer(Device& dev, const ViewUniforms& view, const std::string& technique);
// The lookup parameters most shadow techniques share, as the uniform buffer
// "<technique>.params": Block, the technique's own block (its uniforms.h), holds
// the light's view-projection and (bias, map size, shadow alpha, 0), in that order.
template <class Block>
Buffer createLightLookupParams(Device& dev, const ViewUniforms& view, float bias, uint32_t size,
                               float shadowAlpha, const std::string& technique) {
  static_assert(sizeof(Block) == sizeof(glm::mat4) + sizeof(glm::vec4), "a mat4 and a vec4");
  const Block p{view.viewProj, glm::vec4(bias, float(size), shadowAlpha, 0.0f)};
  return dev.createBuffer({technique + ".params", Owner::Frame, BufferUsage::Uniform, sizeof p},
                          &p);
}

// Binding numbers shared by every shader, named in render/common/slots.h
// (which the GLSL includes too; render/common/bindings.glsl).
namespace bind {
constexpr uint32_t kView = SB_SLOT_VIEW, kShading = SB_SLOT_SHADING, kPoints = SB_SLOT_POINTS,
                   kColors = SB_SLOT_COLORS, kSegments = SB_SLOT_SEGMENTS,
                   kMeshPositions = SB_SLOT_MESH_POSITIONS, kMeshNormals = SB_SLOT_MESH_NORMALS,
                   kMeshIndices = SB_SLOT_MESH_INDICES,
                   kShadowFirst = SB_SLOT_SHADOW_FIRST;  // 8..15 belong to the shadow technique
}

// Drawing strands and the mesh: the shared vertex shaders and their bindings.
struct Geometry {
  static ShaderCode strandVertexShader(const RenderSettings& s);
  static ShaderCode meshVertexShader();
  static Topology strandTopology(const RenderSettings& s);
  static uint32_t strandVertexCount(const GpuScene& g, const RenderSettings& s);
  // The view's uniforms and the scene's buffers (read only), bound by every geometry pass.
  static Inputs inputs(const GpuScene& g, Buffer viewUbo);
  // One fixed state (d: fragment shader, targets, depth, bindings) drawn over the
  // strands and over the mesh: pipelines "<name>.hair" and "<name>.mesh", each
  // made only when the scene has that geometry.
  struct HairAndMesh {
    Pipeline hair, mesh;
  };
  static HairAndMesh pipelines(Device& dev, PipelineDesc d, const GpuScene& g,
                               const RenderSettings& s, const std::string& name);
};

// What the shading passes need to call a shadow technique's lookup, declared
// once: its shader, its defines and its inputs (whose slots, bindings, sampled
// textures and graph reads every pass that shades through it takes).
struct ShadowLookup {
  std::string shader;     // defines float shadowVisibility(vec3 worldPos)
  ShaderDefines defines;  // e.g. SB_OPAQUE_SHADOW from OpaqueShadow
  Inputs inputs;
};

// A number a technique reports about its last frame (render --json "counters"),
// e.g. the nodes a deep shadow map kept.
struct Counter {
  std::string name;
  double value = 0;
};

// A self-shadowing technique: its own passes (from the light) and a GLSL
// lookup, `float shadowVisibility(vec3 worldPos)`, that shading passes include
// as <shadow>.
class ShadowTechnique {
 public:
  virtual ~ShadowTechnique() = default;
  virtual std::string name() const = 0;
  virtual void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) = 0;
  // Work done once before the first frame (e.g. sizing fragment lists); may run frames.
  virtual void prepare(Device& /*dev*/) {}
  virtual void addPasses(FrameGraph& graph, Device& dev) = 0;
  // Depth complexity from the light, for techniques that measure it.
  virtual std::optional<DepthComplexity> depthComplexity() const { return std::nullopt; }
  // Problems found while rendering (e.g. a fragment-list overflow, a layer cap hit).
  virtual std::vector<std::string> warnings(Device& /*dev*/) { return {}; }
  // Whether its visibility never rises away from the light (checked by
  // --invariants along the probe ray); fom's Fourier ringing does not promise it.
  // Its descriptor's capability (render/common/unit.h).
  bool monotone() const;
  // Numbers about the last frame (read back from the device), for the JSON.
  virtual std::vector<Counter> counters(Device& /*dev*/) { return {}; }
  // Non-empty (the reason) when part of the timed work is an emulation (avsm
  // without fragment-shader interlock), as OitTechnique::timingEmulated.
  virtual std::string timingEmulated() const { return {}; }
  // Techniques with tiers (rt: "software" | "ray_query"): the one in use,
  // known after setup (render JSON "tier"); empty for the others. tierReason:
  // why that one (render JSON "tier_reason").
  virtual std::string tier() const { return {}; }
  virtual std::string tierReason() const { return {}; }
  // The lookup, declared once: its shader, defines and inputs.
  virtual ShadowLookup lookup() const = 0;
};

// An order-independent transparency technique: composites the hair over the
// opaque result ("color", "depth" written by the mesh pass, or cleared by the
// technique itself when the scene has no mesh). Hair is shaded through the
// shadow technique's lookup (render/shading/hair_shading.glsl).
struct OitTargets {
  Texture color, depth;
  bool opaqueDrawn = false;  // false: the technique's first pass clears them
  // With --msaa N > 1, color and depth have N samples and `resolved` is the
  // single-sampled frame colour the technique's last pass resolves color into.
  Texture resolved;
};

class HairShading;

class OitTechnique {
 public:
  virtual ~OitTechnique() = default;
  virtual std::string name() const = 0;
  virtual void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                     const HairShading& shading, const OitTargets& targets) = 0;
  // True when prepare() does work; the renderer then draws the opaque depth first.
  virtual bool needsPrepare() const { return false; }
  virtual void prepare(Device& /*dev*/) {}
  // Reads the opaque result (targets' color and depth) when one was drawn, writes color.
  virtual void addPasses(FrameGraph& graph, Device& dev) = 0;
  virtual std::optional<DepthComplexity> depthComplexity() const { return std::nullopt; }
  virtual std::vector<std::string> warnings(Device& /*dev*/) { return {}; }
  // Numbers about the last frame (read back from the device), for the render
  // JSON's "counters": e.g. fragments a full node pool dropped, merge steps an
  // emulation did, layers peeled, fragments lost to depth ties.
  virtual std::vector<Counter> counters(Device& /*dev*/) { return {}; }
  // Non-empty (the reason) when part of the timed work is an emulation whose
  // cost is not the technique's real cost (mlab without fragment-shader
  // interlock): the JSON and the reports mark the timing "emulated".
  virtual std::string timingEmulated() const { return {}; }
  // As ShadowTechnique::tier and tierReason.
  virtual std::string tier() const { return {}; }
  virtual std::string tierReason() const { return {}; }
  // Whether it renders into multisampled frame targets (--msaa N > 1). Those
  // that keep per-pixel data (fragment lists, peeled layers, accumulation
  // targets, occupancy maps) say no and the renderer refuses --msaa for them.
  // Its descriptor's capability (render/common/unit.h).
  bool multisampled() const;
};

// Groups of 64 for a 1D compute pass over `items`, as a 2D grid (x, y) so that
// no dimension passes the 65535 guaranteed by GL and Vulkan. Shaders index with
// linearInvocation() (common/invocation.glsl) and bounds-check.
inline glm::uvec2 dispatchGroups(uint32_t items) {
  const uint32_t groups = (items + 63) / 64;
  const uint32_t y = (groups + 65534) / 65535;
  return {(groups + y - 1) / std::max(y, 1u), std::max(y, 1u)};
}

// By name from the registry (render/common/unit.h). Throws InputError for
// unknown names/options (with the closest valid name).
std::unique_ptr<ShadowTechnique> makeShadowTechnique(const Spec& spec);
std::unique_ptr<OitTechnique> makeOitTechnique(const Spec& spec);

}  // namespace sb
