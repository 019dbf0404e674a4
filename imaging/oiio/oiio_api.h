// What the OpenImageIO module (libsb_oiio.so, built from imaging/oiio/module.cpp) gives the
// harness. OpenImageIO pulls in about 260 shared libraries whose loading cost every process
// about 0.6 s before main; loaded with dlopen on the first image read or write, only the
// processes that touch an image file pay it. Errors come back as text (empty: success), so
// that no exception crosses the module's boundary.
#pragma once

#include <string>
#include <vector>

namespace sb::oiio {

// The drawing surface of a figure grid (cli/figure_command.cpp).
struct Canvas;

struct Api {
  // Encodes w x h x channels samples into `path` as `format` ("png" or "openexr").
  // `type` 0: uint8, 1: uint16, 2: half (from float samples), 3: float. `samples` holds
  // uint8, uint16 or float values, as `type` says (half is written from floats).
  std::string (*write)(const std::string& path, const std::string& format, int w, int h,
                       int channels, int type, const void* samples);
  // Decodes subimage 0 as float samples, channels interleaved, row 0 at the top.
  std::string (*read)(const std::string& path, int& w, int& h, int& channels,
                      std::vector<float>& samples);
  // An RGB float canvas of w x h, white; freed with canvasFree.
  Canvas* (*canvasCreate)(int w, int h);
  void (*canvasFree)(Canvas*);
  void (*canvasFill)(Canvas*, int x0, int x1, int y0, int y1, float r, float g, float b);
  // Text in DejaVu Sans; false where there is no font.
  bool (*canvasText)(Canvas*, int x, int y, const std::string& text, int size, float r, float g,
                     float b);
  // An image file fitted into a tile x tile box at (x, y), letterboxed; false when unreadable.
  bool (*canvasPaste)(Canvas*, const std::string& file, int x, int y, int tile);
  // The canvas's samples (w x h x 3 floats) into `out`.
  void (*canvasPixels)(Canvas*, float* out);
};

// The module's entry point, looked up by name after dlopen.
#define SB_OIIO_ENTRY "sb_oiio_api"
using EntryFn = const Api* (*)();

// The module, loaded on first use (next to the executable, or SB_OIIO_MODULE); throws
// DeviceError naming the file and dlerror() when it cannot be loaded.
const Api& api();

}  // namespace sb::oiio
