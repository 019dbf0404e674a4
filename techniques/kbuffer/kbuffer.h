// k-buffer transparency as TressFX 4 resolves its per-pixel linked lists (AMD
// TressFX 4.0; the k-buffer of Bavoil et al. 2007): every visible hair
// fragment is shaded and stored in its pixel's list (the A-buffer's lists,
// techniques/abuffer), then a resolve keeps the k nearest of each pixel,
// blends the others as a tail in arrival order and the k back to front over
// it (kbuffer_math.glsl). The lists live in a node pool of `nodes` entries (0:
// as many as the counting pass found): a full pool drops fragments, which are
// counted (counter "dropped_fragments") and reported in a warning, never
// silently. The lists are put in submission order before the resolve, so the
// tail is the same on every run and on both APIs.
#pragma once

#include "techniques/abuffer/abuffer.h"

namespace sb {

class OptionReader;

class KBufferOit : public ABufferOit {
 public:
  struct Options {
    int k = 8;           // 1..32
    uint64_t nodes = 0;  // node pool entries; 0: the counted fragments
  };
  static constexpr int kMaxK = 32;  // kbuffer_math.glsl's SB_KBUFFER_MAX
  explicit KBufferOit(Options o) : ABufferOit(~0ull), o_(o) {}
  std::string name() const override { return "kbuffer"; }
  std::vector<std::string> warnings(Device& dev) override;
  std::vector<Counter> counters(Device& dev) override;

 protected:
  std::string resolveShader() const override { return "techniques/kbuffer/resolve.comp"; }
  ShaderDefines resolveDefines() const override;
  uint64_t poolEntries(uint64_t counted) const override;

 private:
  Options o_;
};

}  // namespace sb
