// The small platform-neutral window the window platforms (`--platform window`)
// open, for commands that take input (`strandbench view`): events, title, size.
// GLFW stays inside backends/ (backends/window/glfw_window.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sb {

struct InputEvent {
  enum class Kind { Key, Button, Cursor, Scroll };
  Kind kind = Kind::Key;
  // Key: "A".."Z", "0".."9", "Left", "Right", "Up", "Down", "PageUp",
  // "PageDown", "Space", "Tab", "Escape", "Enter", "F1".."F12"; empty for
  // keys without a name here.
  std::string key;
  int button = 0;      // Button: 0 left, 1 right, 2 middle
  bool press = true;   // Key, Button: pressed (or repeated) or released
  bool shift = false;  // modifiers held (Key, Button)
  bool ctrl = false;
  bool alt = false;
  double x = 0, y = 0;  // Cursor: position in window pixels (top-left origin); Scroll: offsets
};

class Window {
 public:
  virtual ~Window() = default;
  // The events since the last call (processes the window system's queue).
  virtual std::vector<InputEvent> poll() = 0;
  // The user asked to close the window (close button).
  virtual bool closeRequested() const = 0;
  virtual void setTitle(const std::string& title) = 0;
  // Framebuffer size in pixels; 0x0 while minimized.
  virtual uint32_t width() const = 0;
  virtual uint32_t height() const = 0;
  // As a user would: resize the window, minimize or restore it (for scripts
  // and tests). Waits until the window system has applied it.
  virtual void resize(uint32_t width, uint32_t height) = 0;
  virtual void minimize(bool minimized) = 0;
};

}  // namespace sb
