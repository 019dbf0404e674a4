// Loads libsb_oiio.so on first use (imaging/oiio/oiio_api.h says why).
#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <system_error>

#include "base/errors.h"
#include "imaging/oiio/oiio_api.h"

namespace sb::oiio {

namespace {

// SB_OIIO_MODULE, else the module beside the running executable (the build folder holds
// strandbench, sb_tests and libsb_oiio.so together).
std::string modulePath() {
  if (const char* e = std::getenv("SB_OIIO_MODULE"); e && *e) return e;
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return (ec ? std::filesystem::path("libsb_oiio.so") : exe.parent_path() / "libsb_oiio.so")
      .string();
}

const Api* load() {
  const std::string path = modulePath();
  // Never closed: OpenImageIO keeps threads and caches for the life of the process.
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* e = ::dlerror();
    throw DeviceError("cannot load the image module " + path +
                      " (image files need it): " + (e ? e : "unknown error"));
  }
  auto entry = reinterpret_cast<EntryFn>(::dlsym(handle, SB_OIIO_ENTRY));
  if (!entry) throw DeviceError("the image module " + path + " has no " SB_OIIO_ENTRY);
  return entry();
}

}  // namespace

const Api& api() {
  static std::once_flag once;
  static const Api* loaded = nullptr;
  std::call_once(once, [] { loaded = load(); });
  return *loaded;
}

}  // namespace sb::oiio
