// tinyobjloader's implementation, compiled into the OBJ fuzz target with the fuzz build's
// instrumentation. Debian's libtinyobjloader.so (what sb_scenes links) has no coverage
// counters or ASan checks, so the fuzzer would be blind inside the parser; definitions in
// the executable take precedence over the shared library's, so parseObj calls these.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
