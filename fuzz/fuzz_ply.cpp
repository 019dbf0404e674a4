// libFuzzer target: sb::parsePly (PLY strands, ascii and binary) on the fuzzer's bytes, as
// is and with points_per_strand (the reading of files without a 'strand' element), and
// sb::parsePlyMesh (mesh=) on the same bytes: the two share the header and body reader.
#include "fuzz/fuzz_check.h"
#include "scenes/mesh_loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  sbfuzz::run([&] { return sb::parsePly(data, size, sbfuzz::kName); }, sbfuzz::checkStrands);
  // 2..6 points per strand, varying with the input so that vertex counts divide and not.
  const auto perStrand = uint32_t(2 + size % 5);
  sbfuzz::run([&] { return sb::parsePly(data, size, sbfuzz::kName, perStrand); },
              sbfuzz::checkStrands);
  sbfuzz::run([&] { return sb::parsePlyMesh(data, size, sbfuzz::kName); }, sbfuzz::checkMesh);
  return 0;
}
