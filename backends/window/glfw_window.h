// The GLFW window under both window platforms: GL (a 4.5 core context made
// current) and Vulkan (no client API; the platform makes a surface).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "backends/window.h"

struct GLFWwindow;

namespace sb {

class GlfwWindow : public Window {
 public:
  enum class Api { OpenGL, None };
  // Throws DeviceError ("no display: ...") when GLFW cannot start (no
  // DISPLAY/WAYLAND_DISPLAY, or the window system refuses) or makes no window.
  GlfwWindow(Api api, uint32_t width, uint32_t height, const std::string& title);
  ~GlfwWindow() override;
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  std::vector<InputEvent> poll() override;
  bool closeRequested() const override;
  void setTitle(const std::string& title) override;
  uint32_t width() const override;
  uint32_t height() const override;
  void resize(uint32_t width, uint32_t height) override;
  void minimize(bool minimized) override;

  GLFWwindow* handle() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
  std::vector<InputEvent> events_;
};

// GLFW's own description of its last error, or "" (for messages).
std::string glfwLastError();

}  // namespace sb
