// The invariants measure (harness/measures/invariants/unit.cpp; render --invariants): the
// checks of harness/invariants.h on a finished run, the reported errors included.
#pragma once

#include <vector>

#include "harness/invariants.h"
#include "harness/render.h"

namespace sb {

struct InvariantsResult : MeasureSlice {
  std::vector<InvariantFailure> failures;
  void json(nlohmann::json& report) const override;
};

// Adds a failure found after the run (a sweep's run-to-run check) to its invariants.
void addInvariantFailure(RenderResult& r, InvariantFailure f);

}  // namespace sb
