// The viewer's state drawn over the image it shows (`strandbench view`, key O):
// text from stb_easy_font rasterized on the CPU into an RGBA8 image (a dark
// translucent box in the top-left corner, the text over it), and a full-screen
// pass (render/common/overlay.frag) that mixes it over a copy of the shown
// image into the texture the window presents. The shown image itself, which
// screenshots write and the numbers describe, is never touched.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "backends/device.h"

namespace sb {

// One line: a label and its value in two columns (the value alone when the
// label is empty), in one colour.
struct OverlayLine {
  std::string label, value;
  std::array<uint8_t, 3> color{235, 235, 235};
  bool operator==(const OverlayLine&) const = default;
};

struct OverlayRaster {
  // width x height RGBA8, straight alpha, rows bottom-up as writeTexture takes them.
  std::vector<uint8_t> rgba8;
  int scale = 1;                    // 2 where the window is large enough
  int boxX = 0, boxY = 0;           // the box's top-left corner (rows from the top)
  int boxWidth = 0, boxHeight = 0;  // clipped to the image
};

// The lines in a box in the top-left corner of a width x height image, the
// rest transparent; ASCII only (stb_easy_font).
OverlayRaster rasterizeOverlay(const std::vector<OverlayLine>& lines, uint32_t width,
                               uint32_t height);

class ViewOverlay {
 public:
  // The texture to present: `shown` (a one-layer colour texture) with `lines`
  // over it, the same size. Composed again only when the lines, the size, the
  // texture or `shownVersion` (bumped by the caller whenever it rewrites
  // `shown`) changed. Outside frames.
  Texture compose(Device& dev, Texture shown, uint64_t shownVersion,
                  const std::vector<OverlayLine>& lines);
  // Frees the textures (the next compose makes them again): before a render,
  // whose memory report holds only its own resources. The pipeline is kept:
  // it holds no memory the device accounts, and the next size reuses it.
  void release(Device& dev);

 private:
  Texture text_, target_;
  Pipeline pipeline_;
  Format format_ = Format::RGBA32F;
  uint32_t width_ = 0, height_ = 0;
  std::vector<OverlayLine> lines_;
  Texture composedFrom_;
  uint64_t composedVersion_ = 0;
  bool composed_ = false;
};

}  // namespace sb
