// GL 4.5 core over OSMesa, loaded with dlopen so libOSMesa's gl* symbols never
// meet another libGL at link time. OSMesa was removed in Mesa 25.1: a fallback.
#include <dlfcn.h>

#include <string>
#include <vector>

#include "backends/device.h"
#include "backends/gl/gl_platform.h"

namespace sb {
namespace {

// From GL/osmesa.h, repeated here because that header drags in GL/gl.h.
constexpr int kOSMesaFormat = 0x22, kOSMesaRGBA = 0x1908, kOSMesaDepthBits = 0x30,
              kOSMesaProfile = 0x33, kOSMesaCoreProfile = 0x34, kOSMesaMajor = 0x36,
              kOSMesaMinor = 0x37;
constexpr unsigned kGLUnsignedByte = 0x1401;

using OSMesaContext = void*;
using CreateContextAttribsFn = OSMesaContext (*)(const int*, OSMesaContext);
using MakeCurrentFn = unsigned char (*)(OSMesaContext, void*, unsigned, int, int);
using DestroyContextFn = void (*)(OSMesaContext);
using GetProcAddressFn = void* (*)(const char*);

class OSMesaPlatform : public GLPlatform {
 public:
  OSMesaPlatform() {
    for (const char* lib : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
      handle_ = dlopen(lib, RTLD_NOW | RTLD_LOCAL);
      if (handle_) break;
    }
    if (!handle_)
      throw DeviceError(
          "no GL context: libOSMesa not found (install libosmesa6; removed in Mesa >= 25.1; "
          "--platform egl may work)");
    auto create =
        reinterpret_cast<CreateContextAttribsFn>(dlsym(handle_, "OSMesaCreateContextAttribs"));
    makeCurrent_ = reinterpret_cast<MakeCurrentFn>(dlsym(handle_, "OSMesaMakeCurrent"));
    destroy_ = reinterpret_cast<DestroyContextFn>(dlsym(handle_, "OSMesaDestroyContext"));
    getProc_ = reinterpret_cast<GetProcAddressFn>(dlsym(handle_, "OSMesaGetProcAddress"));
    if (!create || !makeCurrent_ || !destroy_ || !getProc_)
      throw DeviceError("no GL context: libOSMesa lacks OSMesaCreateContextAttribs (too old)");
    const int attribs[] = {kOSMesaFormat,
                           kOSMesaRGBA,
                           kOSMesaDepthBits,
                           0,
                           kOSMesaProfile,
                           kOSMesaCoreProfile,
                           kOSMesaMajor,
                           4,
                           kOSMesaMinor,
                           5,
                           0};
    context_ = create(attribs, nullptr);
    if (!context_)
      throw DeviceError(
          "no GL context: OSMesa could not create an OpenGL 4.5 core context (the driver may "
          "offer less than 4.5)");
    // OSMesa needs a colour buffer to be current; rendering goes to FBOs.
    buffer_.resize(4 * 4 * 4);
    if (!makeCurrent_(context_, buffer_.data(), kGLUnsignedByte, 4, 4))
      throw DeviceError("no GL context: OSMesaMakeCurrent failed");
    entered();
  }
  ~OSMesaPlatform() override {
    if (context_) destroy_(context_);
    // The library stays loaded: Mesa keeps thread-local state that may outlive us.
    left();
  }
  void makeCurrent() override { makeCurrent_(context_, buffer_.data(), kGLUnsignedByte, 4, 4); }
  std::string name() const override { return "osmesa"; }
  void* getProcAddress(const char* fn) override { return getProc_(fn); }

 private:
  void* handle_ = nullptr;
  OSMesaContext context_ = nullptr;
  MakeCurrentFn makeCurrent_ = nullptr;
  DestroyContextFn destroy_ = nullptr;
  GetProcAddressFn getProc_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GLPlatform> createOSMesaPlatform() { return std::make_unique<OSMesaPlatform>(); }

}  // namespace sb
