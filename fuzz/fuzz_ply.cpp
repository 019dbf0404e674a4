// libFuzzer target: sb::parsePly (PLY strands, ascii and binary) on the fuzzer's bytes.
#include "fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  sbfuzz::run([&] { return sb::parsePly(data, size, sbfuzz::kName); }, sbfuzz::checkStrands);
  return 0;
}
