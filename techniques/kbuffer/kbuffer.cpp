#include "techniques/kbuffer/kbuffer.h"

#include "base/options.h"

namespace sb {

ShaderDefines KBufferOit::resolveDefines() const {
  ShaderDefines d;
  d.defines.push_back({"SB_KBUFFER_K", std::to_string(o_.k)});
  return d;
}

uint64_t KBufferOit::poolEntries(uint64_t counted) const {
  return o_.nodes == 0 ? counted : o_.nodes;
}

std::vector<Counter> KBufferOit::counters(Device& dev) {
  return {{"pool_nodes", double(pool_)}, {"dropped_fragments", double(status(dev)[1])}};
}

std::vector<std::string> KBufferOit::warnings(Device& dev) {
  const uint32_t dropped = status(dev)[1];
  if (dropped == 0) return {};
  return {"kbuffer: node pool overflow: " + std::to_string(dropped) + " fragments dropped (nodes=" +
          std::to_string(pool_) + ", " + std::to_string(complexity_.total) + " needed)"};
}

}  // namespace sb
