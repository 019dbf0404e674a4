// libFuzzer target: sb::parseTfx (AMD TressFX .tfx, versions 3 and 4) on the fuzzer's bytes.
#include "fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  sbfuzz::run([&] { return sb::parseTfx(data, size, sbfuzz::kName); }, sbfuzz::checkStrands);
  return 0;
}
