// GL 4.5 core in a GLFW window (`--platform window`): the context of the
// window, made current; vsync off (swap interval 0) so a present costs the
// copy and the swap, not a wait for the display.
#include <GLFW/glfw3.h>

#include "backends/gl/gl_platform.h"
#include "backends/window/glfw_window.h"

namespace sb {
namespace {

class WindowGLPlatform : public GLPlatform {
 public:
  WindowGLPlatform(uint32_t width, uint32_t height, const std::string& title)
      : window_(GlfwWindow::Api::OpenGL, width, height, title) {
    glfwMakeContextCurrent(window_.handle());
    glfwSwapInterval(0);
    entered();
  }
  ~WindowGLPlatform() override {
    glfwMakeContextCurrent(nullptr);
    left();
  }
  void makeCurrent() override { glfwMakeContextCurrent(window_.handle()); }
  std::string name() const override { return "window"; }
  void* getProcAddress(const char* fn) override {
    return reinterpret_cast<void*>(glfwGetProcAddress(fn));
  }
  Window* window() override { return &window_; }
  std::string presentMode() const override {
    return "GLFW window, blit to the default framebuffer and swap, swap interval 0 (vsync off)";
  }
  void swapBuffers() override { glfwSwapBuffers(window_.handle()); }

 private:
  GlfwWindow window_;
};

}  // namespace

std::unique_ptr<GLPlatform> createWindowGLPlatform(uint32_t width, uint32_t height,
                                                   const std::string& title) {
  return std::make_unique<WindowGLPlatform>(width, height, title);
}

}  // namespace sb
