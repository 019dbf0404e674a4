// FNV-1a over 64 bits: a stable hash of bytes for cache keys and the digests of generated
// files (not a defence against anyone crafting a collision), and its 16 hex digits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace sb {

inline constexpr std::uint64_t kFnvOffset = 0xCBF29CE484222325ull;

inline std::uint64_t fnv1a(std::uint64_t h, const void* data, std::size_t n) {
  const auto* b = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001B3ull;
  return h;
}

inline std::string hex64(std::uint64_t v) {
  static const char* hex = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, v >>= 4) out[std::size_t(i)] = hex[v & 15];
  return out;
}

}  // namespace sb
