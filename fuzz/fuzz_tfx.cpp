// libFuzzer target: sb::parseTfx (AMD TressFX .tfx: binary versions 3 and 4, and the text
// form of 1.x/2.x) on the fuzzer's bytes. Warnings, like errors, must name the input.
#include "fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::vector<std::string> warnings;
  sbfuzz::run([&] { return sb::parseTfx(data, size, sbfuzz::kName, &warnings); },
              sbfuzz::checkStrands);
  for (const std::string& w : warnings) {
    if (w.find(sbfuzz::kName) == std::string::npos) sbfuzz::bug("warning without the name: " + w);
  }
  return 0;
}
