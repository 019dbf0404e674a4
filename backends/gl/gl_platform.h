// Where a GL context comes from: EGL surfaceless (default; Mesa and NVIDIA) or
// OSMesa (fallback; loaded with dlopen). Rendering always goes to FBOs.
#pragma once

#include <memory>
#include <string>

namespace sb {

class GLPlatform {
 public:
  virtual ~GLPlatform() = default;
  virtual std::string name() const = 0;  // "egl" | "osmesa"
  virtual void* getProcAddress(const char* name) = 0;
};

// Both make a GL 4.5 core context current on the calling thread, or throw DeviceError.
std::unique_ptr<GLPlatform> createEGLPlatform();
std::unique_ptr<GLPlatform> createOSMesaPlatform();

}  // namespace sb
