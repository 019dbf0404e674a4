// libFuzzer target: sb::parseHair (Cem Yuksel's binary HAIR format) on the fuzzer's bytes.
#include "fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  sbfuzz::run([&] { return sb::parseHair(data, size, sbfuzz::kName); }, sbfuzz::checkStrands);
  return 0;
}
