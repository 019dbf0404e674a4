// --oit fake: fake transparency.
#include "render/common/unit.h"

#include "techniques/fake/fake.h"

SB_TECHNIQUE({.makeOit = [](const OptionReader&) { return std::make_unique<FakeTransparency>(); }});
