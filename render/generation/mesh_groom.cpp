#include "render/generation/mesh_groom.h"

#include <bit>

#include "render/generation/groom_table.h"

namespace sb {

void uploadMeshGroom(Device& dev, const Scene& scene, GpuScene& gpu) {
  const Groom& g = scene.groom;
  if (g.empty())
    throw InputError("--geometry mesh: the scene has no groom (guides= or instances=)");
  // The mesh shader makes every strand of every instance: it does not read the level of
  // detail's per-instance shares and guide order (generate.comp does), so it refuses rather
  // than draw the full model.
  if (g.hasLod())
    throw InputError(
        "--geometry mesh: the level of detail (lod=, lod_pixels=) is not on the "
        "mesh path yet; use --geometry compute or cpu");
  const uint64_t segments = g.totalStrands() * (g.points - 1);
  if (segments > UINT32_MAX)
    throw InputError("--geometry mesh: " + std::to_string(segments) +
                     " segments, more than one draw takes (2^32 - 1)");
  std::vector<uint32_t> table(SB_GROOM_TABLE_HEADER, 0u);
  table[SB_GROOM_TABLE_GUIDES] = g.guideCount;
  table[SB_GROOM_TABLE_POINTS] = g.points;
  table[SB_GROOM_TABLE_STRANDS] = g.strands;
  table[SB_GROOM_TABLE_SEGMENTS] = static_cast<uint32_t>(segments);
  const float floats[] = {g.spread, g.offset, g.noise, g.clump, g.alongStep, scene.hairAlpha, 1.0f};
  const uint32_t at[] = {SB_GROOM_TABLE_RULE,     SB_GROOM_TABLE_RULE + 1, SB_GROOM_TABLE_RULE + 2,
                         SB_GROOM_TABLE_RULE + 3, SB_GROOM_TABLE_ALONG,    SB_GROOM_TABLE_ALPHA,
                         SB_GROOM_TABLE_WIDEN};
  for (std::size_t i = 0; i < std::size(floats); ++i)
    table[at[i]] = std::bit_cast<uint32_t>(floats[i]);
  table.insert(table.end(), g.neighbours.begin(), g.neighbours.end());
  table[SB_GROOM_TABLE_SEEDS] = static_cast<uint32_t>(table.size());
  table.insert(table.end(), g.instanceSeeds.begin(), g.instanceSeeds.end());
  table[SB_GROOM_TABLE_PLACEMENTS] = static_cast<uint32_t>(table.size());
  for (const glm::vec4& p : g.placements)
    for (int k = 0; k < 4; ++k) table.push_back(std::bit_cast<uint32_t>(p[k]));

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
