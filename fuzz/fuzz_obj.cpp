// libFuzzer target: sb::parseObj, the OBJ mesh loader (tinyobjloader underneath), on the
// fuzzer's bytes as text.
#include <string>

#include "fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sbfuzz::run([&] { return sb::parseObj(text, sbfuzz::kName); }, sbfuzz::checkMesh);
  return 0;
}
