#include "view_window.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <chrono>
#include <stdexcept>
#include <thread>

namespace habuffer::view {

struct WindowCallbacks {
  static ViewWindow& of(GLFWwindow* w) { return *static_cast<ViewWindow*>(glfwGetWindowUserPointer(w)); }
  static void scroll(GLFWwindow* w, double, double dy) {
    if (!ImGui::GetIO().WantCaptureMouse) of(w).pending_.scroll += dy;
  }
  static void key(GLFWwindow* w, int key, int, int action, int) {
    if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
    InputEvents& e = of(w).pending_;
    switch (key) {
      case GLFW_KEY_P: e.psnr = true; break;
      case GLFW_KEY_O: e.next_overlay = true; break;
      case GLFW_KEY_T: e.next_technique = true; break;
      case GLFW_KEY_G: e.toggle_gui = true; break;
      case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
      default: break;
    }
  }
};

namespace {

std::string glfw_error() {
  const char* what = nullptr;
  glfwGetError(&what);
  return what != nullptr ? what : "unknown reason";
}

}  // namespace

ViewWindow::ViewWindow(Extent size, const std::string& title) {
  if (glfwInit() != GLFW_TRUE)
    throw std::runtime_error("no window system (GLFW: " + glfw_error() + "); under no display run it in xvfb-run");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
#if HABUFFER_GL_DEBUG
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
#endif
  window_ = glfwCreateWindow(static_cast<int>(size.x), static_cast<int>(size.y), title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string why = glfw_error();
    glfwTerminate();
    throw std::runtime_error("no OpenGL 4.5 core window (GLFW: " + why + ")");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(window_, this);
  // Ours first: ImGui's callbacks, installed next, call them after their own.
  glfwSetScrollCallback(window_, WindowCallbacks::scroll);
  glfwSetKeyCallback(window_, WindowCallbacks::key);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written beside the user's files
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
}

ViewWindow::~ViewWindow() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool ViewWindow::should_close() const { return glfwWindowShouldClose(window_) == GLFW_TRUE; }

InputEvents ViewWindow::poll() {
  glfwPollEvents();
  double x = 0, y = 0;
  glfwGetCursorPos(window_, &x, &y);
  const bool down = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  if (down && dragging_) {
    pending_.drag_x += x - last_x_;
    pending_.drag_y += y - last_y_;
  }
  dragging_ = down && (dragging_ || !ImGui::GetIO().WantCaptureMouse);
  last_x_ = x;
  last_y_ = y;
  InputEvents out = pending_;
  pending_ = {};
  return out;
}

Extent ViewWindow::framebuffer() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {static_cast<std::uint32_t>(std::max(w, 0)), static_cast<std::uint32_t>(std::max(h, 0))};
}

void ViewWindow::resize(Extent size) {
  glfwSetWindowSize(window_, static_cast<int>(size.x), static_cast<int>(size.y));
  // A window manager, or a loaded machine, may take a while; the loop ends as soon as the size arrives.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (framebuffer() != size && std::chrono::steady_clock::now() < until) {
    glfwWaitEventsTimeout(0.01);
  }
}

void ViewWindow::begin_gui() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ViewWindow::end_gui() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());  // saves and restores the GL state it sets
}

void ViewWindow::swap() { glfwSwapBuffers(window_); }

}  // namespace habuffer::view
