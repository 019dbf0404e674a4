#include "cli/view_overlay.h"

#include <stb_easy_font.h>

#include <algorithm>

#include "render/common/composite.h"
#include "render/common/slots.h"

namespace sb {
namespace {

// In font pixels (scaled with the text): stb_easy_font's glyphs span rows 0..9
// of a line, descenders included, so 11 leaves a gap of one row between lines.
constexpr int kMargin = 6, kPadding = 4, kLineStep = 11, kGlyphRows = 10, kColumnGap = 8;
constexpr uint8_t kBoxAlpha = 170;  // dark enough for white text over white hair

// stb_easy_font takes char* (it never writes it): a copy keeps the caller's const.
int textWidth(const std::string& text) {
  std::string copy = text;
  return stb_easy_font_width(copy.data());
}

}  // namespace

OverlayRaster rasterizeOverlay(const std::vector<OverlayLine>& lines, uint32_t width,
                               uint32_t height) {
  OverlayRaster out;
  const int w = int(width), h = int(height);
  out.rgba8.assign(std::size_t(w) * h * 4, 0);
  if (lines.empty() || w == 0 || h == 0) return out;
  int labelWidth = 0;
  for (const auto& l : lines)
    if (!l.label.empty()) labelWidth = std::max(labelWidth, textWidth(l.label) + kColumnGap);
  int textW = 0;
  for (const auto& l : lines)
    textW = std::max(textW, l.label.empty() ? textWidth(l.value) : labelWidth + textWidth(l.value));
  const int textH = int(lines.size()) * kLineStep - (kLineStep - kGlyphRows);
  const int boxW = textW + 2 * kPadding, boxH = textH + 2 * kPadding;
  // Twice the size where the doubled box still leaves most of the picture free.
  out.scale = 2 * (kMargin + boxW) <= w * 3 / 4 && 2 * (kMargin + boxH) <= h / 2 ? 2 : 1;
  const int s = out.scale;
  out.boxX = std::min(s * kMargin, w);
  out.boxY = std::min(s * kMargin, h);
  out.boxWidth = std::min(s * boxW, w - out.boxX);
  out.boxHeight = std::min(s * boxH, h - out.boxY);

  // (x, y) from the top-left corner, clipped to the box: rows are stored bottom-up.
  auto fill = [&](int x0, int y0, int x1, int y1, std::array<uint8_t, 4> rgba) {
    x0 = std::max(x0, out.boxX);
    y0 = std::max(y0, out.boxY);
    x1 = std::min(x1, out.boxX + out.boxWidth);
    y1 = std::min(y1, out.boxY + out.boxHeight);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        std::copy(rgba.begin(), rgba.end(),
                  out.rgba8.begin() + (std::ptrdiff_t(h - 1 - y) * w + x) * 4);
  };
  fill(out.boxX, out.boxY, out.boxX + out.boxWidth, out.boxY + out.boxHeight, {0, 0, 0, kBoxAlpha});

  // stb_easy_font writes 4 vertices (x, y, z: float; colour: 4 bytes) per quad,
  // about 270 bytes a character; its quads are axis-aligned, on whole font pixels.
  struct Vertex {
    float x, y, z;
    uint8_t color[4];
  };
  std::vector<Vertex> quads;
  auto print = [&](const std::string& text, int x, int y, const std::array<uint8_t, 3>& c) {
    std::string copy = text;
    quads.resize(copy.size() * 500 / sizeof(Vertex) + 4);  // stb truncates past the end
    const int n = stb_easy_font_print(float(x), float(y), copy.data(), nullptr, quads.data(),
                                      int(quads.size() * sizeof(Vertex)));
    for (int q = 0; q < n; ++q) {
      const Vertex* v = &quads[std::size_t(q) * 4];
      float x0 = v[0].x, x1 = v[0].x, y0 = v[0].y, y1 = v[0].y;
      for (int i = 1; i < 4; ++i) {
        x0 = std::min(x0, v[i].x);
        x1 = std::max(x1, v[i].x);
        y0 = std::min(y0, v[i].y);
        y1 = std::max(y1, v[i].y);
      }
      fill(int(x0 * s), int(y0 * s), int(x1 * s), int(y1 * s), {c[0], c[1], c[2], 255});
    }
  };
  const int left = kMargin + kPadding;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int y = kMargin + kPadding + int(i) * kLineStep;
    const OverlayLine& l = lines[i];
    if (l.label.empty()) {
      print(l.value, left, y, l.color);
    } else {
      print(l.label, left, y, l.color);
      print(l.value, left + labelWidth, y, l.color);
    }
  }
  return out;
}

Texture ViewOverlay::compose(Device& dev, Texture shown, uint64_t shownVersion,
                             const std::vector<OverlayLine>& lines) {
  const TextureDesc d = dev.describe(shown);
  bool redraw = false;
  const bool formatChanged = d.format != format_;
  if (pipeline_ && formatChanged) {  // its target's format is the shown texture's
    dev.destroy(pipeline_);
    pipeline_ = {};
  }
  if (!target_ || formatChanged || d.width != width_ || d.height != height_) {
    release(dev);
    format_ = d.format;
    width_ = d.width;
    height_ = d.height;
    text_ = dev.createTexture({"view.overlay.text", Owner::View, Format::RGBA8, width_, height_});
    // Float like the shown image, so that where there is no text the window
    // shows exactly what it would without the overlay.
    target_ = dev.createTexture({"view.overlay", Owner::View, d.format, width_, height_});
    lines_.clear();
    redraw = true;
  }
  if (redraw || lines != lines_) {
    dev.writeTexture(text_, rasterizeOverlay(lines, width_, height_).rgba8);
    lines_ = lines;
    redraw = true;
  }
  if (redraw || !composed_ || shown.id != composedFrom_.id || shownVersion != composedVersion_) {
    const Pass pass = Pass("view.overlay")
                          .color(target_, LoadOp::Clear)
                          .sample(SB_SLOT_OVERLAY_IMAGE, shown)
                          .sample(SB_SLOT_OVERLAY_TEXT, text_);
    if (!pipeline_)
      pipeline_ = fullScreenPipeline(dev, pass, "view.overlay", "view",
                                     "render/common/overlay.frag", {}, {});
    dev.beginFrame();
    pass.draw(dev, pipeline_, 3);
    dev.endFrame();
    composedFrom_ = shown;
    composedVersion_ = shownVersion;
    composed_ = true;
  }
  return target_;
}

void ViewOverlay::release(Device& dev) {
  dev.destroy(text_);
  dev.destroy(target_);
  text_ = {};
  target_ = {};
  width_ = height_ = 0;
  composed_ = false;
}

}  // namespace sb
