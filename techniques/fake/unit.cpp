// --oit fake: fake transparency.
#include "render/common/unit.h"

#include "techniques/fake/fake.h"

SB_TECHNIQUE(
    {.name = "fake",
     .family = Family::Transparency,
     .folder = "fake",
     .paper = "Yuksel & Keyser 2008, section 4",
     .help = "fake transparency (Yuksel & Keyser 2008, section 4): the strands in 3 interleaved "
             "subsets, each drawn opaque into its own image, the 3 images blended equally",
     .caps = {.multisampling = true,
              .meshRefusal = "it splits the strands' segment list into its subsets"},
     .makeOit = [](const OptionReader&) { return std::make_unique<FakeTransparency>(); }});
