// libFuzzer target: sb::parseTfxMesh (TressFX's text .tfxmesh: bones, vertices with
// normals and skinning, triangles) on the fuzzer's bytes.
#include "fuzz/fuzz_check.h"
#include "scenes/mesh_loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  sbfuzz::run([&] { return sb::parseTfxMesh(data, size, sbfuzz::kName); }, sbfuzz::checkMesh);
  return 0;
}
