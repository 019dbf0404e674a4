#include "techniques/abuffer/abuffer.h"

#include <cstring>

#include "render/common/shader_library.h"
#include "render/shading/hair_shading.h"
#include "techniques/abuffer/uniforms.h"

namespace sb {

namespace {
// As in techniques/abuffer/abuffer.glsl (16 is the accumulation, 17 the counts).
constexpr uint32_t kOffsets = SB_SLOT_ABUFFER_OFFSETS, kCursor = SB_SLOT_ABUFFER_CURSOR,
                   kFragments = SB_SLOT_ABUFFER_FRAGMENTS, kStatus = SB_SLOT_ABUFFER_STATUS;
constexpr uint32_t kSize = SB_SLOT_ABUFFER_SIZE;  // the resolve's size uniform
constexpr std::size_t kFragmentBytes = 32;
constexpr uint32_t kPageSlots[] = {kFragments, SB_SLOT_ABUFFER_PAGE1, SB_SLOT_ABUFFER_PAGE2,
                                   SB_SLOT_ABUFFER_PAGE3, SB_SLOT_ABUFFER_PAGE4};
}  // namespace

void ABufferOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                       const HairShading& shading, const OitTargets& targets) {
  setupCommon(dev, scene, s, shading, targets);
  offsets_ =
      dev.createBuffer({name() + ".offsets", Owner::Oit, BufferUsage::Storage, pixels() * 4ull});
  cursor_ =
      dev.createBuffer({name() + ".cursor", Owner::Oit, BufferUsage::Storage, pixels() * 4ull});
  status_ = dev.createBuffer({name() + ".status", Owner::Oit, BufferUsage::Storage, 16});
  // Sized by prepare()'s count.
  pageShift_ = poolPageShift(dev.info(), kFragmentBytes);
  pages_.resize(kPages);
  for (uint32_t page = 0; page < kPages; ++page)
    pages_[page] = dev.createBuffer(
        {name() + ".fragments" + (page ? ".page" + std::to_string(page) : std::string()),
         Owner::Oit, BufferUsage::Storage, kFragmentBytes});
  const AbufferSize size{glm::uvec4(pixels(), s.width, s.height, 0)};
  sizeUbo_ =
      dev.createBuffer({name() + ".size", Owner::Frame, BufferUsage::Uniform, sizeof size}, &size);
  makePipelines(dev);
}

// The fill and the resolve, compiled for the pages the pool uses (abuffer.glsl).
void ABufferOit::makePipelines(Device& dev) {
  dev.destroy(fill_);
  dev.destroy(resolve_);
  ShaderDefines pool;
  pool.defines = {{"SB_ABUFFER_PAGES", std::to_string(pagesUsed_)},
                  {"SB_ABUFFER_PAGE_SHIFT", std::to_string(pageShift_)}};
  fill_ = hairPipeline(dev, fillPass(), "techniques/abuffer/fill.frag", pool);
  const ShaderCode comp = loadShader(resolveShader(), resolveDefines().add(pool));
  PipelineDesc c = resolvePass().pipeline(dev, name() + ".resolve", name());
  c.compute = &comp;
  resolve_ = dev.createPipeline(c);
}

uint64_t ABufferOit::poolEntries(uint64_t counted) const {
  if (counted > maxFragments_)
    throw InputError(
        "A-buffer: the scene has " + std::to_string(counted) +
        " visible hair fragments, over the limit max_fragments=" + std::to_string(maxFragments_) +
        " (" + std::to_string(counted * kFragmentBytes >> 20) +
        " MiB); lower the resolution or raise the limit");
  return counted;
}

void ABufferOit::prepare(Device& dev) {
  ListLayout layout = countFragments(dev);
  pool_ = poolEntries(complexity_.total);
  if (pool_ < complexity_.total) {
    // A fixed pool (kbuffer's nodes): a pixel keeps what fits below the pool's
    // end; the fill counts the rest as dropped (status[1]).
    std::vector<uint32_t> capacity(layout.offsets.size());
    for (std::size_t p = 0; p < capacity.size(); ++p)
      capacity[p] = static_cast<uint32_t>(std::min<uint64_t>(
          complexity_.counts[p], pool_ - std::min<uint64_t>(pool_, layout.offsets[p])));
    dev.updateBuffer(counts_, capacity.data(), capacity.size() * 4);
  }
  dev.updateBuffer(offsets_, layout.offsets.data(), layout.offsets.size() * 4);
  // The pool in pages that each fit one storage binding.
  const uint32_t pages = sizePoolPages(dev, pages_, pool_, pageShift_, kFragmentBytes,
                                       name() + ": the fragment pool", "lower the resolution");
  if (pages != pagesUsed_) {
    pagesUsed_ = pages;
    makePipelines(dev);
  }
}

// The lists: the fill appends to them, the resolve sorts and accumulates them.
Inputs ABufferOit::lists() const {
  Inputs in;
  in.storage(AccumComposite::kAccumBinding, composite_.accum())
      .storage(kCountsBinding, counts_)
      .storage(kOffsets, offsets_)
      .storage(kCursor, cursor_)
      .storage(kStatus, status_);
  for (uint32_t page = 0; page < kPages; ++page) in.storage(kPageSlots[page], pages_[page]);
  return in;
}

Pass ABufferOit::fillPass() const { return hairPass(name() + ".fill", true).inputs(lists()); }

Pass ABufferOit::resolvePass() const {
  return Pass(name() + ".resolve").uniform(kSize, sizeUbo_).inputs(lists());
}

void ABufferOit::addPasses(FrameGraph& graph, Device& dev) {
  const Pass fill = fillPass(), resolve = resolvePass(), composite = composite_.pass();
  graph.add(name(), {fill, resolve, composite}, [this, &dev, fill, resolve] {
    dev.fillBuffer(cursor_, 0);
    dev.fillBuffer(status_, 0);
    fill.draw(dev, fill_, hairVertices());
    const glm::uvec2 g = dispatchGroups(pixels());
    resolve.dispatch(dev, resolve_, g.x, g.y);
    composite_.record(dev);
  });
}

std::vector<uint32_t> ABufferOit::status(Device& dev) {
  const auto bytes = dev.readBuffer(status_);
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), words.size() * 4);
  return words;
}

std::vector<std::string> ABufferOit::warnings(Device& dev) {
  if (status(dev)[0]) return {"eye-space A-buffer overflow: fragments were dropped"};
  return {};
}

}  // namespace sb
