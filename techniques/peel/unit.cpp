// --oit peel: the transparency reference.
#include "render/common/unit.h"

#include "techniques/peel/peel.h"

namespace sb {
namespace {
struct O {
  uint32_t layers;
};
const OptionTable<O> kOptions({opt::layersCap(&O::layers)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.name = "peel",
              .family = Family::Transparency,
              .folder = "peel",
              .paper = "",
              .help = "ground truth: depth peeling from the eye, front to back, every layer",
              .options = kOptions.infos(),
              .stepped = SteppedOption{"layers", true, 1, 65536},
              .caps = {.exact = true,
                       .msaaRefusal = "peels whole-pixel layers by (depth, primitive) keys kept in "
                                      "per-pixel state buffers: per-sample peeling needs N times "
                                      "that state and a sample-rate pass per layer; not written"},
              .makeOit = [](const OptionReader& r) {
                return std::make_unique<PeelOit>(kOptions.read(r).layers);
              }});
