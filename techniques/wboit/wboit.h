// Weighted blended order-independent transparency (McGuire & Bavoil 2013,
// "Weighted Blended Order-Independent Transparency", JCGT 2(2)), as the thesis
// (section 3.3, eq. 25) uses it for hair: one accumulation pass into an
// RGBA16F/RGBA32F target (c a w, a w) and an R32F revealage target, then a
// full-screen resolve (wboit_math.glsl).
#pragma once

#include "techniques/weighted/weighted.h"

namespace sb {

class WeightedBlendedOit : public BlendedOitBase {
 public:
  // weightEq: 0 (const), 7, 8, 9 or 10; precisionBits: 16 or 32.
  WeightedBlendedOit(int weightEq, int precisionBits)
      : weightEq_(weightEq), precisionBits_(precisionBits) {}
  std::string name() const override { return "wboit"; }

 protected:
  Config config() const override;

 private:
  int weightEq_;
  int precisionBits_;
};

}  // namespace sb
