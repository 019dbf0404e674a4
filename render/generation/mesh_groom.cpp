#include "render/generation/mesh_groom.h"

#include <bit>

#include "render/generation/groom_table.h"

namespace sb {

void uploadMeshGroom(Device& dev, const Scene& scene, GpuScene& gpu) {
  const Groom& g = scene.groom;
  if (g.empty())
    throw InputError("--geometry mesh: the scene has no groom (guides= or instances=)");
  const uint64_t segments = g.totalStrands() * (g.points - 1);
  if (segments > UINT32_MAX)
    throw InputError("--geometry mesh: " + std::to_string(segments) +
                     " segments, more than one draw takes (2^32 - 1)");
  std::vector<uint32_t> table(SB_GROOM_TABLE_HEADER, 0u);
  table[SB_GROOM_TABLE_GUIDES] = g.guideCount;
  table[SB_GROOM_TABLE_POINTS] = g.points;
  table[SB_GROOM_TABLE_STRANDS] = g.strands;
  table[SB_GROOM_TABLE_SEGMENTS] = static_cast<uint32_t>(segments);
  table[SB_GROOM_TABLE_INSTANCES] = g.instanceCount();
  const float floats[] = {g.spread, g.offset, g.noise, g.clump, g.alongStep, scene.hairAlpha};
  const uint32_t at[] = {SB_GROOM_TABLE_RULE,     SB_GROOM_TABLE_RULE + 1, SB_GROOM_TABLE_RULE + 2,
                         SB_GROOM_TABLE_RULE + 3, SB_GROOM_TABLE_ALONG,    SB_GROOM_TABLE_ALPHA};
  for (std::size_t i = 0; i < std::size(floats); ++i)
    table[at[i]] = std::bit_cast<uint32_t>(floats[i]);
  table.insert(table.end(), g.neighbours.begin(), g.neighbours.end());
  table[SB_GROOM_TABLE_SEEDS] = static_cast<uint32_t>(table.size());
  table.insert(table.end(), g.instanceSeeds.begin(), g.instanceSeeds.end());
  table[SB_GROOM_TABLE_PLACEMENTS] = static_cast<uint32_t>(table.size());
  for (const glm::vec4& p : g.placements)
    for (int k = 0; k < 4; ++k) table.push_back(std::bit_cast<uint32_t>(p[k]));
  // The level of detail, as generate.comp reads it (every instance's, all kept without one).
  table[SB_GROOM_TABLE_LODS] = static_cast<uint32_t>(table.size());
  for (const GroomInstanceLod& l : g.lods)
    table.insert(table.end(), {l.first, l.kept, std::bit_cast<uint32_t>(l.widen), 0u});
  table[SB_GROOM_TABLE_ORDER] = static_cast<uint32_t>(table.size());
  table.insert(table.end(), g.guideOrder.begin(), g.guideOrder.end());

  auto input = [&](const std::string& name, const void* data, std::size_t bytes) {
    return dev.createBuffer({"scene." + name, Owner::Scene, BufferUsage::Storage, bytes}, data);
  };
  gpu.points =
      input("guide_points", g.guidePoints.data(), g.guidePoints.size() * sizeof(glm::vec4));
  gpu.colors =
      input("guide_colors", g.guideColors.data(), g.guideColors.size() * sizeof(glm::vec4));
  gpu.segments = input("groom_table", table.data(), table.size() * sizeof(uint32_t));
  gpu.segmentCount = static_cast<uint32_t>(segments);
}

}  // namespace sb
