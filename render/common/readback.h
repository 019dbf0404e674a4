#pragma once
// A device buffer read back as an array of T (whole elements; a tail shorter
// than one T is dropped): what a technique reads to build or count on the CPU.
#include <cstring>
#include <vector>

#include "backends/device.h"

namespace sb {

template <class T>
std::vector<T> readBufferAs(Device& dev, Buffer b) {
  const std::vector<uint8_t> bytes = dev.readBuffer(b);
  std::vector<T> v(bytes.size() / sizeof(T));
  if (!v.empty()) std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
  return v;
}

}  // namespace sb
