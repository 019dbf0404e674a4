#include "backends/window/glfw_window.h"

#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdlib>

#include "base/errors.h"  // DeviceError

namespace sb {
namespace {

// GLFW is initialised once for all windows of the process and terminated with
// the last one (GLFW keeps process-wide state; it must be called from the main thread).
int g_windows = 0;

std::string keyName(int key) {
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return std::string(1, char('A' + key - GLFW_KEY_A));
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return std::string(1, char('0' + key - GLFW_KEY_0));
  if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F12) {
    std::string name = "F";  // appended, not "F" + ...: GCC 12 warns (-Wrestrict) on that
    name += std::to_string(key - GLFW_KEY_F1 + 1);
    return name;
  }
  switch (key) {
    case GLFW_KEY_LEFT:
      return "Left";
    case GLFW_KEY_RIGHT:
      return "Right";
    case GLFW_KEY_UP:
      return "Up";
    case GLFW_KEY_DOWN:
      return "Down";
    case GLFW_KEY_PAGE_UP:
      return "PageUp";
    case GLFW_KEY_PAGE_DOWN:
      return "PageDown";
    case GLFW_KEY_SPACE:
      return "Space";
    case GLFW_KEY_TAB:
      return "Tab";
    case GLFW_KEY_ESCAPE:
      return "Escape";
    case GLFW_KEY_ENTER:
      return "Enter";
    default:
      return "";
  }
}

GlfwWindow* owner(GLFWwindow* w) { return static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w)); }

}  // namespace

std::string glfwLastError() {
  const char* text = nullptr;
  glfwGetError(&text);
  return text ? text : "";
}

GlfwWindow::GlfwWindow(Api api, uint32_t width, uint32_t height, const std::string& title) {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!x11 || !*x11) && (!wayland || !*wayland))
    throw DeviceError(
        "no display: the window platform needs one (DISPLAY and WAYLAND_DISPLAY are unset); "
        "run under xvfb-run for a virtual display, or use a headless platform");
  if (g_windows == 0 && !glfwInit())
    throw DeviceError("no display: GLFW could not start (" + glfwLastError() +
                      "); run under xvfb-run for a virtual display, or use a headless platform");
  ++g_windows;
  glfwDefaultWindowHints();
  if (api == Api::OpenGL) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glfwWindowHint(GLFW_STENCIL_BITS, 0);
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);  // the PNG's values, not converted
  } else {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  }
  window_ = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), title.c_str(),
                             nullptr, nullptr);
  if (!window_) {
    const std::string why = glfwLastError();
    if (--g_windows == 0) glfwTerminate();
    throw DeviceError("no window: GLFW could not open a " + std::to_string(width) + "x" +
                      std::to_string(height) + " window" +
                      (api == Api::OpenGL ? " with an OpenGL 4.5 core context" : "") + " (" + why +
                      ")");
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) {
    InputEvent e;
    e.kind = InputEvent::Kind::Key;
    e.key = keyName(key);
    e.press = action != GLFW_RELEASE;
    e.shift = mods & GLFW_MOD_SHIFT;
    e.ctrl = mods & GLFW_MOD_CONTROL;
    e.alt = mods & GLFW_MOD_ALT;
    owner(w)->events_.push_back(e);
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int mods) {
    InputEvent e;
    e.kind = InputEvent::Kind::Button;
    e.button = button == GLFW_MOUSE_BUTTON_RIGHT ? 1 : button == GLFW_MOUSE_BUTTON_MIDDLE ? 2 : 0;
    e.press = action == GLFW_PRESS;
    e.shift = mods & GLFW_MOD_SHIFT;
    e.ctrl = mods & GLFW_MOD_CONTROL;
    e.alt = mods & GLFW_MOD_ALT;
    owner(w)->events_.push_back(e);
  });
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    InputEvent e;
    e.kind = InputEvent::Kind::Cursor;
    e.x = x;
    e.y = y;
    owner(w)->events_.push_back(e);
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double x, double y) {
    InputEvent e;
    e.kind = InputEvent::Kind::Scroll;
    e.x = x;
    e.y = y;
    owner(w)->events_.push_back(e);
  });
}

GlfwWindow::~GlfwWindow() {
  glfwDestroyWindow(window_);
  if (--g_windows == 0) glfwTerminate();
}

std::vector<InputEvent> GlfwWindow::poll() {
  glfwPollEvents();
  std::vector<InputEvent> out;
  out.swap(events_);
  return out;
}

bool GlfwWindow::closeRequested() const { return glfwWindowShouldClose(window_); }

void GlfwWindow::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

uint32_t GlfwWindow::width() const {
  if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED)) return 0;
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return static_cast<uint32_t>(w > 0 && h > 0 ? w : 0);
}

uint32_t GlfwWindow::height() const {
  if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED)) return 0;
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return static_cast<uint32_t>(w > 0 && h > 0 ? h : 0);
}

void GlfwWindow::resize(uint32_t width, uint32_t height) {
  glfwSetWindowSize(window_, static_cast<int>(width), static_cast<int>(height));
  // The X server applies it asynchronously: wait (a bounded time) until it has.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (std::chrono::steady_clock::now() < until) {
    glfwWaitEventsTimeout(0.01);
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (w == static_cast<int>(width) && h == static_cast<int>(height)) break;
  }
}

void GlfwWindow::minimize(bool minimized) {
  if (minimized)
    glfwIconifyWindow(window_);
  else
    glfwRestoreWindow(window_);
  glfwWaitEventsTimeout(0.05);
}

}  // namespace sb
