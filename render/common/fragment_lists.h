// Per-pixel fragment lists stored contiguously (pixel p owns entries
// [offsets[p], offsets[p] + counts[p])), used by the exact ground truths:
// a counting pass sizes them, a prefix sum places them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/common/technique.h"

namespace sb {

struct ListLayout {
  std::vector<uint32_t> offsets;  // exclusive prefix sum of the counts
  DepthComplexity complexity;
};

// From the read-back per-pixel counts (uint32 each).
ListLayout layoutFromCounts(const std::vector<uint8_t>& countBytes);

// A fragment pool larger than one storage binding (DeviceInfo::
// maxStorageBufferBytes) is split into pages: page p holds the entries
// [p << shift, (p + 1) << shift). The shift is the largest whose page of
// `entryBytes` entries fits one binding (31 at most: indices are 32-bit).
// SB_POOL_PAGE_BYTES, where set, is a smaller limit in bytes: a test hook
// that makes a small scene's pool split.
uint32_t poolPageShift(const DeviceInfo& device, std::size_t entryBytes);

// Sizes the first pages of a pool of `entries` entries of `entryBytes` (at
// least one entry) to hold it, pages of 2^pageShift entries, and returns how
// many it uses; those after keep their size. More than pages.size(): an
// InputError that starts with `what` ("abuffer: the fragment pool") and ends
// with `advice`.
uint32_t sizePoolPages(Device& dev, const std::vector<Buffer>& pages, uint64_t entries,
                       uint32_t pageShift, std::size_t entryBytes, const std::string& what,
                       const std::string& advice);

// A pipeline for `pass` (Pass::pipeline: its slots, no colour targets) that
// counts the hair fragments of every pixel into the storage buffer at
// `countsBinding`, depth-tested (never written) against an opaque depth when
// the pass has one.
Pipeline makeHairCountPipeline(Device& dev, const RenderSettings& s, const Pass& pass,
                               uint32_t countsBinding, const std::string& technique);

// A compute pipeline for `pass` (its slots; the size uniform at 0) finishing
// one peel layer (render/common/peel_advance.comp). nodesBinding and
// offsetsBinding are 0 when layers are not stored in lists.
Pipeline makePeelAdvancePipeline(Device& dev, const Pass& pass, uint32_t stateBinding,
                                 uint32_t peeledBinding, uint32_t offsetsBinding,
                                 uint32_t nodesBinding, const std::string& technique);

}  // namespace sb
