// --oit abuffer: the second transparency reference.
#include "render/common/unit.h"

#include "techniques/abuffer/abuffer.h"

namespace sb {
namespace {
struct O {
  uint64_t maxFragments;
};
const OptionTable<O> kOptions(
    {opt::integer(&O::maxFragments, "max_fragments", 50000000, 1, 1000000000,
                  "most fragments stored (32 bytes each), 1..1000000000")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = [](const OptionReader& r) {
                return std::make_unique<ABufferOit>(kOptions.read(r).maxFragments);
              }});
