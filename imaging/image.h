// CPU images: GPU readback -> Image, and image files (PNG, EXR) in and out.
//
// Conventions:
//  - Image rows are in file order: row 0 is the TOP of the picture. GPU readback
//    (both backends, see design.md "Pixel parity") has row 0 at the BOTTOM;
//    imageFromRows() does the one vertical flip.
//  - Pixel values are stored exactly as given: colour is linear 0..1, and no
//    colour-space transfer (sRGB) and no alpha (un)premultiplication is applied
//    on write or read. A PNG therefore holds round(clamp(v, 0, 1) * 255) of the
//    raw value, and reads back as that code / 255.
//  - Errors caused by the user (a path, a file) throw sb::InputError naming the
//    path and the problem; misuse by the caller (inconsistent sizes) throws
//    std::invalid_argument.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sb {

struct Image {
  int width = 0, height = 0, channels = 4;
  // Row-major, interleaved channels, row 0 = top of the picture (file order).
  std::vector<float> pixels;

  Image() = default;
  // A width x height image with `channels` channels, every sample set to `fill`.
  Image(int w, int h, int c = 4, float fill = 0.0f);

  std::size_t index(int x, int y, int c) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
            static_cast<std::size_t>(x)) *
               static_cast<std::size_t>(channels) +
           static_cast<std::size_t>(c);
  }
  float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }
  bool empty() const { return width <= 0 || height <= 0; }
};

// Sample format of GPU readback bytes.
enum class PixelType {
  UNorm8,   // one byte per sample, value = byte / 255
  Float32,  // one native-endian IEEE float per sample
};

std::size_t bytesPerSample(PixelType t);

// GPU readback -> Image. `bytes` holds h tightly packed rows of w * channels
// samples, row 0 = BOTTOM of the picture; the result is flipped so that row 0 is
// the top. Throws std::invalid_argument if bytes.size() != w * h * channels *
// bytesPerSample(t) or a dimension is not positive.
Image imageFromRows(const std::vector<std::uint8_t>& bytes, int w, int h, PixelType t,
                    int channels);

// Sample format of a written file.
enum class ImageBitDepth {
  Default,  // .png -> U8, .exr -> F32
  U8,       // PNG only: round(clamp(v, 0, 1) * 255); NaN -> 0
  U16,      // PNG only: round(clamp(v, 0, 1) * 65535); NaN -> 0
  F16,      // EXR only: half float
  F32,      // EXR only: full float, exact round trip
};

// Writes `img` to `path`, format chosen by the extension (case-insensitive):
// .png (1-4 channels, 8 or 16 bit) or .exr (half or float). Channel names are
// Y, YA, RGB or RGBA for 1-4 channels.
//
// Atomic: the file is written to "<path>.tmp-XXXXXX" in the same folder and
// renamed over `path`, so `path` is either the old file or the complete new one;
// the temporary file is removed on failure. (No fsync: this protects against a
// failed or interrupted write, not against power loss.)
//
// Deterministic: the same Image gives byte-identical files (no time stamps or
// software names are written).
//
// Throws InputError (message names the path) for an unknown extension, a bit
// depth the format cannot hold, a missing or unwritable folder, or any write
// failure; std::invalid_argument for an empty or inconsistent Image.
void writeImage(const Image& img, const std::string& path,
                ImageBitDepth depth = ImageBitDepth::Default);

// Reads subimage 0 of any file OpenImageIO can read, converted to float with 4
// channels: 1 channel -> (g, g, g, 1), 2 channels -> (g, g, g, a), 3 -> (r, g, b, 1),
// more than 4 -> the first 4. Integer formats map to 0..1 (code / max code).
// Throws InputError naming the file on any failure.
Image readImage(const std::string& path);

// Loads the image module (OpenImageIO, imaging/oiio/) now rather than at the first image
// file. A run that will write images calls it before its memory check, so that the module's
// address space counts against the host's budget (an address-space limit) there.
void loadImageModule();

}  // namespace sb
