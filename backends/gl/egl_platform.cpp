// GL 4.5 core over EGL without any surface: Mesa's surfaceless platform, or
// the EGL device platform (NVIDIA) when surfaceless is absent.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "backends/device.h"
#include "backends/gl/gl_platform.h"

namespace sb {
namespace {

bool hasExtension(const char* list, const char* ext) {
  if (!list) return false;
  const std::size_t n = std::strlen(ext);
  for (const char* p = list; (p = std::strstr(p, ext)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

std::string eglErrorText() {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(eglGetError()));
  return std::string("EGL error ") + code;
}

class EGLPlatform : public GLPlatform {
 public:
  EGLPlatform() {
    const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (getPlatformDisplay && hasExtension(clientExt, "EGL_MESA_platform_surfaceless"))
      display_ = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display_ == EGL_NO_DISPLAY && getPlatformDisplay &&
        hasExtension(clientExt, "EGL_EXT_platform_device")) {
      auto queryDevices =
          reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      EGLDeviceEXT devices[8];
      EGLint count = 0;
      if (queryDevices && queryDevices(8, devices, &count) && count > 0)
        display_ = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
    }
    if (display_ == EGL_NO_DISPLAY)
      throw DeviceError(
          "no GL context: EGL offers no surfaceless or device display (is Mesa's EGL, "
          "libegl-mesa0, installed? --platform osmesa may work)");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display_, &major, &minor))
      throw DeviceError("no GL context: eglInitialize failed (" + eglErrorText() +
                        "; is a Mesa DRI driver installed? --platform osmesa may work)");
    if (!eglBindAPI(EGL_OPENGL_API))
      throw DeviceError("no GL context: EGL cannot bind desktop OpenGL (" + eglErrorText() + ")");

    const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint numConfigs = 0;
    const char* dispExt = eglQueryString(display_, EGL_EXTENSIONS);
    if (!hasExtension(dispExt, "EGL_KHR_no_config_context")) {
      if (!eglChooseConfig(display_, configAttribs, &config, 1, &numConfigs) || numConfigs < 1)
        throw DeviceError("no GL context: EGL has no OpenGL config (" + eglErrorText() + ")");
    }
    const EGLint ctxAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, ctxAttribs);
    if (context_ == EGL_NO_CONTEXT)
      throw DeviceError("no GL context: EGL could not create an OpenGL 4.5 core context (" +
                        eglErrorText() + "; the driver may offer less than 4.5)");
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw DeviceError("no GL context: EGL eglMakeCurrent without a surface failed (" +
                        eglErrorText() + ")");
    entered();
  }
  ~EGLPlatform() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    // eglTerminate is left out on purpose: other devices in this process may
    // share the display (EGL displays are per-process singletons).
    left();
  }
  void makeCurrent() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_);
  }
  std::string name() const override { return "egl"; }
  void* getProcAddress(const char* fn) override {
    return reinterpret_cast<void*>(eglGetProcAddress(fn));
  }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GLPlatform> createEGLPlatform() { return std::make_unique<EGLPlatform>(); }

}  // namespace sb
