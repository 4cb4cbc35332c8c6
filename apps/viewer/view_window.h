/// @file
/// habuffer-view's window: GLFW with an OpenGL 4.5 core context (a debug
/// context in debug builds), and Dear ImGui on it. The only place that knows
/// GLFW or ImGui's backends; one per process.
#pragma once

#include <functional>
#include <string>

#include "habuffer/extent.h"

struct GLFWwindow;

namespace habuffer::view {

/// What the mouse and keys asked for since the last poll (ignoring what ImGui took).
struct InputEvents {
  double drag_x = 0, drag_y = 0;  ///< left-button drag, in pixels
  double scroll = 0;              ///< wheel steps
  bool psnr = false, next_overlay = false, next_technique = false, toggle_gui = false;
};

class ViewWindow {
 public:
  /// Opens a window whose framebuffer is `size` (GlError-like std::runtime_error
  /// naming the reason: no display, no OpenGL 4.5 core context).
  ViewWindow(Extent size, const std::string& title);
  ~ViewWindow();
  ViewWindow(const ViewWindow&) = delete;
  ViewWindow& operator=(const ViewWindow&) = delete;

  [[nodiscard]] bool should_close() const;
  /// Polls the window system; returns this poll's input.
  InputEvents poll();
  /// The framebuffer's size now (it follows resizes; 0x0 while minimized).
  [[nodiscard]] Extent framebuffer() const;
  /// Asks for a framebuffer of `size` and waits (at most 5 s) until the window system gives it.
  void resize(Extent size);
  /// Starts the GUI's frame (before any ImGui call).
  void begin_gui();
  /// Draws the GUI into the default framebuffer, with GL state saved and restored around it.
  void end_gui();
  void swap();

 private:
  GLFWwindow* window_ = nullptr;
  InputEvents pending_;
  double last_x_ = 0, last_y_ = 0;
  bool dragging_ = false;
  friend struct WindowCallbacks;
};

}  // namespace habuffer::view
