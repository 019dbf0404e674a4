// A small render for tests: one frame or a few, no warm-up, a square image.
#pragma once

#include <string>

#include "harness/render.h"

namespace sbtest {

inline sb::RenderRequest smallRender(const std::string& backend, const std::string& scene,
                                     const std::string& shadow, const std::string& oit,
                                     uint32_t size, int repeat = 1) {
  sb::RenderRequest req;
  req.backend = backend;
  req.scene = scene;
  req.shadow = shadow;
  req.oit = oit;
  req.width = req.height = size;
  req.repeat = repeat;
  req.warmup = 0;
  return req;
}

}  // namespace sbtest
