// The accumulation buffer of the exact transparency techniques and the pass
// that puts it over the opaque result ("oit.composite").
#pragma once

#include "techniques/common/technique.h"

namespace sb {

class AccumComposite {
 public:
  static constexpr uint32_t kAccumBinding = SB_SLOT_OIT_ACCUM;  // vec4 per pixel, premultiplied
  void setup(Device& dev, const RenderSettings& s, Buffer viewUbo, const OitTargets& targets,
             const std::string& technique);
  Buffer accum() const { return accum_; }
  // The composite pass (clearing the target first when nothing opaque was drawn).
  Pass pass() const;
  // Records it.
  void record(Device& dev) const;

 private:
  RenderSettings settings_;
  OitTargets targets_;
  Buffer accum_, viewUbo_;
  Pipeline pipeline_;
};

}  // namespace sb
