#include "render/common/fragment_lists.h"

#include <cstdlib>
#include <cstring>

#include "render/common/shader_library.h"

namespace sb {

namespace {
constexpr uint32_t kSizeBinding = SB_SLOT_PEEL_ADVANCE_SIZE;  // peel_advance.comp's SIZE_BINDING

std::string bytesText(uint64_t bytes) {
  return std::to_string(bytes) + " bytes" +
         (bytes >> 20 ? " (" + std::to_string(bytes >> 20) + " MiB)" : std::string());
}
}  // namespace

ListLayout layoutFromCounts(const std::vector<uint8_t>& countBytes) {
  ListLayout l;
  const std::size_t n = countBytes.size() / sizeof(uint32_t);
  l.offsets.resize(n);
  l.complexity.counts.resize(n);
  uint64_t covered = 0;
  for (std::size_t i = 0; i < n; ++i) {
    uint32_t c = 0;
    std::memcpy(&c, countBytes.data() + i * sizeof(uint32_t), sizeof c);
    if (l.complexity.total > 0xFFFFFFFFull)
      throw InputError("fragment lists need more than 2^32 entries; lower the resolution");
    l.offsets[i] = static_cast<uint32_t>(l.complexity.total);
    l.complexity.counts[i] = c;
    l.complexity.total += c;
    l.complexity.max = std::max(l.complexity.max, c);
    covered += c > 0;
  }
  l.complexity.mean =
      covered ? static_cast<double>(l.complexity.total) / static_cast<double>(covered) : 0.0;
  return l;
}

uint32_t poolPageShift(const DeviceInfo& device, std::size_t entryBytes) {
  uint64_t most = device.maxStorageBufferBytes ? device.maxStorageBufferBytes : ~0ull;
  if (const char* hook = std::getenv("SB_POOL_PAGE_BYTES"); hook && *hook)
    most = std::min<uint64_t>(most, std::strtoull(hook, nullptr, 10));
  uint32_t shift = 0;
  while (shift < 31 && (uint64_t(entryBytes) << (shift + 1)) <= most) ++shift;
  return shift;
}

uint32_t sizePoolPages(Device& dev, const std::vector<Buffer>& pages, uint64_t entries,
                       uint32_t pageShift, std::size_t entryBytes, const std::string& what,
                       const std::string& advice) {
  entries = std::max<uint64_t>(entries, 1);
  const uint64_t perPage = 1ull << pageShift, used = (entries + perPage - 1) / perPage;
  if (used > pages.size())
    throw InputError(
        what + ", " + bytesText(entries * entryBytes) + ", needs " + std::to_string(used) +
        " storage bindings of at most " + bytesText(perPage * entryBytes) + " on this device; " +
        std::to_string(pages.size()) + (pages.size() == 1 ? " is" : " are") + " bound: " + advice);
  for (uint64_t page = 0; page < used; ++page)
    dev.setBufferSize(pages[page], std::min(perPage, entries - page * perPage) * entryBytes);
  return static_cast<uint32_t>(used);
}

Pipeline makeHairCountPipeline(Device& dev, const RenderSettings& s, const Pass& pass,
                               uint32_t countsBinding, const std::string& technique) {
  ShaderDefines defs;
  defs.defines.push_back({"COUNTS_BINDING", std::to_string(countsBinding)});
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode frag = loadShader("render/common/count.frag", defs);
  PipelineDesc d = pass.pipeline(dev, technique + ".count", technique);
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(s);
  d.depthWrite = false;  // tested only, also where the pass clears the depth
  d.depthCompare = CompareOp::Less;
  return dev.createPipeline(d);
}

Pipeline makePeelAdvancePipeline(Device& dev, const Pass& pass, uint32_t stateBinding,
                                 uint32_t peeledBinding, uint32_t offsetsBinding,
                                 uint32_t nodesBinding, const std::string& technique) {
  ShaderDefines defs;
  defs.defines = {{"STATE_BINDING", std::to_string(stateBinding)},
                  {"PEELED_BINDING", std::to_string(peeledBinding)},
                  {"SIZE_BINDING", std::to_string(kSizeBinding)}};
  if (nodesBinding) {
    defs.defines.push_back({"OFFSETS_BINDING", std::to_string(offsetsBinding)});
    defs.defines.push_back({"NODES_BINDING", std::to_string(nodesBinding)});
  }
  const ShaderCode comp = loadShader("render/common/peel_advance.comp", defs);
  PipelineDesc d = pass.pipeline(dev, technique + ".peel_advance", technique);
  d.compute = &comp;
  return dev.createPipeline(d);
}

}  // namespace sb
