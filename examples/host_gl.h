// What the example host apps share that is not habuffer's: a headless
// EGL context, shader compilation with its log, the app's framebuffer, the
// pixel check against an expected image and the hand-made blend it expects. Header-only, included by the
// examples by relative path (no include directory needed).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

namespace host_gl {

// What a point must show, computed by hand: of `covering` (the translucent
// layers covering it: anything with a depth, an RGB and a straight alpha),
// those nearer than `opaque`, sorted near to far, blended front to back
// over it, each alpha rounded to the 8 bits the records keep.
template <class Layer>
std::array<double, 3> blend_in_front(std::vector<const Layer*> covering, const Layer& opaque) {
  covering.erase(std::remove_if(covering.begin(), covering.end(), [&](const Layer* l) { return l->depth >= opaque.depth; }),
                 covering.end());
  std::sort(covering.begin(), covering.end(), [](const Layer* a, const Layer* b) { return a->depth < b->depth; });
  std::array<double, 3> c{0, 0, 0};
  double transmittance = 1.0;
  for (const Layer* l : covering) {
    const double a = std::round(l->a * 255.0) / 255.0, w = transmittance * a;
    c[0] += w * l->r;
    c[1] += w * l->g;
    c[2] += w * l->b;
    transmittance *= 1.0 - a;
  }
  return {c[0] + transmittance * opaque.r, c[1] + transmittance * opaque.g, c[2] + transmittance * opaque.b};
}

inline void check(bool ok, const std::string& what) {
  if (!ok) throw std::runtime_error(what);
}

// A headless OpenGL 4.5 core context (Mesa's surfaceless platform, else the
// first EGL device: NVIDIA's driver).
inline void make_context() {
  EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr)) {
    EGLDeviceEXT device = nullptr;
    EGLint n = 0;
    check(eglQueryDevicesEXT(1, &device, &n) && n > 0, "no EGL display or device");
    display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    check(display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr), "EGL device display failed");
  }
  check(eglBindAPI(EGL_OPENGL_API), "no desktop OpenGL through EGL");
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  const EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  check(context != EGL_NO_CONTEXT, "no OpenGL 4.5 core context");
  check(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context), "eglMakeCurrent failed");
}

inline GLuint compile(GLenum stage, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("shader compile failed: ") + log);
  }
  return shader;
}

inline GLuint link_program(const std::string& vertex, const std::string& fragment) {
  const GLuint program = glCreateProgram();
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  check(ok != 0, "program link failed");
  return program;
}

// The host's framebuffer: a colour and a depth renderbuffer (of `samples`
// samples each when above 0: a multisampled framebuffer).
inline GLuint make_framebuffer(int width, int height, int samples = 0) {
  GLuint colour = 0, depth = 0, framebuffer = 0;
  glCreateRenderbuffers(1, &colour);
  glNamedRenderbufferStorageMultisample(colour, samples, GL_RGBA8, width, height);
  glCreateRenderbuffers(1, &depth);
  glNamedRenderbufferStorageMultisample(depth, samples, GL_DEPTH_COMPONENT24, width, height);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  glNamedFramebufferRenderbuffer(framebuffer, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  check(glCheckNamedFramebufferStatus(framebuffer, GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE, "framebuffer");
  return framebuffer;
}

// The framebuffer's pixels against expected(px, py) (RGB in [0, 1]; a
// negative value leaves its channel unchecked): the channels off by more
// than rounding (1.5/255), the first three printed; prints the largest
// error under `name`.
template <class Expected>
int count_wrong_channels(GLuint framebuffer, int width, int height, Expected expected, const char* name) {
  std::vector<unsigned char> pixels(4 * static_cast<std::size_t>(width) * height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  int wrong = 0;
  float worst = 0.0f;
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px) {
      const std::vector<float> want = expected(px, py);
      for (int k = 0; k < 3; ++k) {
        if (want[k] < 0.0f) continue;
        const float got = pixels[4 * (px + py * width) + k] / 255.0f, error = std::fabs(got - want[k]);
        worst = std::max(worst, error);
        if (error > 1.5f / 255.0f && ++wrong <= 3)
          std::fprintf(stderr, "pixel (%d, %d) channel %d: %.4f, expected %.4f\n", px, py, k, got, want[k]);
      }
    }
  std::printf("%s: %d x %d pixels, largest error %.5f, %d channels off\n", name, width, height, worst, wrong);
  return wrong;
}

}  // namespace host_gl
