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
  // Makes this context current on the calling thread again.
  virtual void makeCurrent() = 0;

 protected:
  // Contexts nest: a device made while another lives (a further reference's, an animation
  // frame's) makes its context current, and when it goes the newest other live one is made
  // current again, so the device that was working goes on working. A platform calls
  // entered() once its context is current and left() at the end of its destructor, after
  // releasing its context.
  void entered();
  void left();
};

// Both make a GL 4.5 core context current on the calling thread, or throw DeviceError.
std::unique_ptr<GLPlatform> createEGLPlatform();
std::unique_ptr<GLPlatform> createOSMesaPlatform();
// A GLFW window of this size with its context (no depth, no sRGB, swap interval 0).
std::unique_ptr<GLPlatform> createWindowGLPlatform(uint32_t width, uint32_t height,
                                                   const std::string& title);

}  // namespace sb
