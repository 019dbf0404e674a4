// Where a GL context comes from: EGL surfaceless (default; Mesa and NVIDIA),
// OSMesa (fallback; loaded with dlopen) or a GLFW window. Rendering always goes
// to FBOs; a window's default framebuffer only receives present()'s blit.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace sb {

class Window;

class GLPlatform {
 public:
  virtual ~GLPlatform() = default;
  virtual std::string name() const = 0;  // "egl" | "osmesa" | "window"
  virtual void* getProcAddress(const char* name) = 0;
  // The window platform: its window (null elsewhere), how it presents, and
  // the buffer swap that shows the default framebuffer's back buffer.
  virtual Window* window() { return nullptr; }
  virtual std::string presentMode() const { return ""; }
  virtual void swapBuffers() {}
};

// Both make a GL 4.5 core context current on the calling thread, or throw DeviceError.
std::unique_ptr<GLPlatform> createEGLPlatform();
std::unique_ptr<GLPlatform> createOSMesaPlatform();
// A GLFW window of this size with its context (no depth, no sRGB, swap interval 0).
std::unique_ptr<GLPlatform> createWindowGLPlatform(uint32_t width, uint32_t height,
                                                   const std::string& title);

}  // namespace sb
