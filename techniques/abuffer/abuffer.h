#pragma once

#include "render/common/hair_oit.h"

namespace sb {

// Exact transparency by an eye-space A-buffer: every hair fragment in front of
// the opaque depth is shaded and stored in its pixel's list (sized by a
// counting pass in prepare()), then each list is sorted by fragment key and
// composited front to back: the cross-check of depth peeling. A list
// overflow is detected and reported, never truncated silently.
class ABufferOit : public HairOit {
 public:
  explicit ABufferOit(uint64_t maxFragments) : maxFragments_(maxFragments) {}
  std::string name() const override { return "abuffer"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void prepare(Device& dev) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  std::vector<std::string> warnings(Device& dev) override;

 protected:
  // What the k-buffer and MLAB (techniques/kbuffer, techniques/mlab) change on
  // the same lists: the resolve shader and its defines, and the number of
  // entries stored (abuffer: all counted ones, over max_fragments an error).
  virtual std::string resolveShader() const { return "techniques/abuffer/resolve.comp"; }
  virtual ShaderDefines resolveDefines() const { return {}; }
  virtual uint64_t poolEntries(uint64_t counted) const;
  // The status words: [0] more fragments than counted, [1] fragments dropped
  // because the pool was full, [2] free for the resolve (a counter).
  std::vector<uint32_t> status(Device& dev);
  uint64_t pool_ = 0;

 private:
  Inputs lists() const;
  Pass fillPass() const;
  Pass resolvePass() const;

  void makePipelines(Device& dev);

  uint64_t maxFragments_;
  Buffer offsets_, cursor_, status_, sizeUbo_;
  // The fragment pool's pages (poolPageShift): the first is "<name>.fragments";
  // the others hold 32 bytes until a pool larger than one binding needs them.
  static constexpr uint32_t kPages = 5;
  std::vector<Buffer> pages_;
  uint32_t pageShift_ = 0, pagesUsed_ = 1;
  Pipeline fill_, resolve_;
};

}  // namespace sb
