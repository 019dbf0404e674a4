#include "techniques/rt/tier.h"

#include <chrono>
#include <numeric>

#include "base/errors.h"
#include "render/common/readback.h"
#include "render/common/unit.h"

namespace sb::rt {

std::vector<Option<TierOptions>> tierOptions() {
  using O = TierOptions;
  std::vector<Option<O>> o = opt::choice(&O::sah, "bvh", "sah", {{"sah", true}, {"median", false}},
                                         "BVH splits: sah (binned surface area heuristic) | "
                                         "median (of the longest axis)");
  for (auto& t : opt::choice(
           &O::tier, "tier", "auto",
           {{"auto", Tier::Auto}, {"software", Tier::Software}, {"ray_query", Tier::RayQuery}},
           "auto (ray_query on a GPU that offers VK_KHR_ray_query; software "
           "elsewhere, CPU devices such as lavapipe included, where ray queries "
           "run in shader code and are far slower) | software (BVH in shader code) | "
           "ray_query (refused, "
           "exit 2, on devices without it); the JSON's tier"))
    o.push_back(std::move(t));
  return o;
}

TierChoice chooseTier(Tier tier, const DeviceInfo& info, const std::string& technique) {
  if (tier == Tier::RayQuery && !info.rayQuery)
    throw UnavailableError(technique + ": tier=ray_query: this device (" + info.backend + ", " +
                               info.device +
                               ") offers no VK_KHR_ray_query (use tier=software or auto)",
                           "a Vulkan device with VK_KHR_ray_query, e.g. Mesa 25.0's lavapipe "
                           "(--driver mesa-25.0; scripts/drivers.sh fetches it)");
  if (tier == Tier::RayQuery) return {true, "tier=ray_query asked for"};
  if (tier == Tier::Software) return {false, "tier=software asked for"};
  if (!info.rayQuery) return {false, "auto: the device offers no VK_KHR_ray_query"};
  // Measured on Mesa 25.0.7's lavapipe (docs/shadow-techniques.md, rt's cost table): ray
  // queries there are a shader-code walk of every box on the ray, 4x to 50x the software
  // tier's frame; a CPU device has no ray-tracing hardware to make up for it.
  if (info.cpuDevice)
    return {false,
            "auto: a CPU device (" + info.device +
                "), where ray queries run in shader code and are far slower than the software "
                "tier's BVH walk"};
  return {true, "auto: the GPU offers VK_KHR_ray_query"};
}

std::vector<Segment> sceneSegments(Device& dev, const GpuScene& scene, const glm::mat4& viewProj,
                                   float worldPerUnitPerW, float width) {
  std::vector<Segment> segs(scene.hasHair() ? scene.segmentCount : 0);
  if (segs.empty()) return segs;
  const auto points = readBufferAs<glm::vec4>(dev, scene.points);
  const auto firsts = readBufferAs<uint32_t>(dev, scene.segments);
  for (uint32_t i = 0; i < segs.size() && i < firsts.size(); ++i) {
    if (firsts[i] + 1 >= points.size()) continue;
    Segment& s = segs[i];
    s.a = glm::vec3(points[firsts[i]]);
    s.b = glm::vec3(points[firsts[i] + 1]);
    const float w = (viewProj * glm::vec4(0.5f * (s.a + s.b), 1.0f)).w;
    s.radius = 0.5f * width * worldPerUnitPerW * std::abs(w);
  }
  return segs;
}

Walk buildWalk(const std::vector<Segment>& segs, bool rayQuery, bool sah) {
  const auto start = std::chrono::steady_clock::now();
  Walk w;
  if (rayQuery) {
    // Ray queries need no BVH of ours: the segments in scene order, one box
    // each; a scene without hair gets one empty box at the origin
    // (packSegments' zero segment, which no ray hits).
    w.bvh.order.resize(segs.size());
    std::iota(w.bvh.order.begin(), w.bvh.order.end(), 0u);
    w.boxes.resize(std::max<std::size_t>(segs.size(), 1));
    for (std::size_t i = 0; i < segs.size(); ++i)
      segmentBounds(segs[i], w.boxes[i][0], w.boxes[i][1]);
  } else {
    w.bvh = buildBvh(segs, 4, sah);
  }
  w.packed = packSegments(w.bvh, segs);
  w.buildMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return w;
}

WalkBuffers uploadWalk(Device& dev, const Walk& w, bool rayQuery, const std::string& prefix,
                       Owner owner) {
  WalkBuffers b;
  if (rayQuery) {
    b.boxes = dev.createBuffer(
        {prefix + "boxes", owner, BufferUsage::Storage, w.boxes.size() * sizeof(w.boxes[0])},
        w.boxes.data());
    b.scene = dev.createAccelerationStructure(prefix + "acceleration_structure", owner, b.boxes,
                                              uint32_t(w.boxes.size()));
  } else {
    b.nodes = dev.createBuffer(
        {prefix + "bvh_nodes", owner, BufferUsage::Storage, w.bvh.nodes.size() * sizeof(Node)},
        w.bvh.nodes.data());
  }
  b.segments = dev.createBuffer(
      {prefix + "segments", owner, BufferUsage::Storage, w.packed.size() * sizeof(glm::vec4)},
      w.packed.data());
  return b;
}

}  // namespace sb::rt
