// --oit kbuffer: the k-buffer as TressFX 4 resolves it.
#include "render/common/unit.h"

#include "techniques/kbuffer/kbuffer.h"

namespace sb {
namespace {
using O = KBufferOit::Options;
const OptionTable<O> kOptions(
    {opt::integer(&O::k, "k", 8, 1, KBufferOit::kMaxK,
                  "fragments kept and sorted per pixel, 1..32"),
     opt::integer(&O::nodes, "nodes", 0, 0, 1000000000,
                  "node pool entries (32 bytes each); 0: the counted fragments; a full "
                  "pool drops fragments (counted and reported), 0..1000000000")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = build<KBufferOit>(kOptions)});
