/* Linked into the executables of an SB_SANITIZE build only (see CMakeLists.txt): dlclose()
 * does nothing, so every library loaded at run time stays mapped until exit, as if opened
 * with RTLD_NODELETE.
 *
 * libEGL and the Vulkan loader dlopen the drivers and layers (Mesa's llvmpipe and lavapipe,
 * the validation layer, every installed ICD) and dlclose them again when a context or
 * instance is destroyed. Once a library is unmapped, LeakSanitizer at exit can neither scan
 * its globals (memory a driver still points to there is reported as leaked: lavapipe leaves
 * 128 bytes this way on every unload) nor name it in a report ("<unknown module>"), so such
 * reports could be neither told apart from leaks in our code nor suppressed by library
 * (google/sanitizers#89, #899). Nothing in strandbench relies on a library being unloaded. */
#include <dlfcn.h>

int dlclose(void* handle) {
  (void)handle;
  return 0;
}
