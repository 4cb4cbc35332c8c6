#include "opencsg_peer.h"

#include <dlfcn.h>
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <opencsg.h>

#include <chrono>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

namespace habuffer::peers {

std::string OpenCsgMethod::name() const {
  return std::string(algorithm == OpenCsgAlgorithm::Goldfeather ? "goldfeather" : "scs") +
         (occlusion_queries ? "+occlusion" : "+convexity");
}

struct CompatContext::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

CompatContext::CompatContext() : state_(std::make_unique<State>()) {
  EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr)) {
    EGLDeviceEXT device = nullptr;
    EGLint n = 0;
    if (!eglQueryDevicesEXT(1, &device, &n) || n == 0) throw std::runtime_error("no EGL display or device");
    d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr)) throw std::runtime_error("the EGL device failed");
  }
  state_->display = d;
  if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error("no desktop OpenGL through EGL");
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT, EGL_NONE};
  state_->context = eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (state_->context == EGL_NO_CONTEXT) throw std::runtime_error("no OpenGL 4.5 compatibility-profile context (OpenCSG needs one)");
  if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context)) {
    eglDestroyContext(d, state_->context);
    throw std::runtime_error("eglMakeCurrent failed");
  }
  // OpenCSG calls GLEW's entry points but leaves glewInit to its host. GLEW
  // (as Debian builds it, for GLX) fills them from the current context and
  // then reports that no GLX display is there (4, GLEW_ERROR_NO_GLX_DISPLAY):
  // harmless here, the GL entry points are set by then. Found through
  // libopencsg's own GLEW, so no GLEW headers or link are needed.
  using GlewInit = unsigned (*)();
  const auto glew_init = reinterpret_cast<GlewInit>(dlsym(RTLD_DEFAULT, "glewInit"));
  const unsigned r = glew_init != nullptr ? glew_init() : 1u;
  if (glew_init == nullptr || (r != 0 && r != 4)) {
    eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(d, state_->context);
    throw std::runtime_error(glew_init == nullptr ? "GLEW's glewInit is not loaded (libopencsg links it)"
                                                  : "glewInit failed with " + std::to_string(r));
  }
}

CompatContext::Current::Current(const CompatContext& c)
    : display_(eglGetCurrentDisplay()),
      context_(eglGetCurrentContext()),
      draw_(eglGetCurrentSurface(EGL_DRAW)),
      read_(eglGetCurrentSurface(EGL_READ)) {
  if (!eglMakeCurrent(c.state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, c.state_->context))
    throw std::runtime_error("eglMakeCurrent of the compatibility context failed");
}

CompatContext::Current::~Current() {
  if (context_ != EGL_NO_CONTEXT)
    eglMakeCurrent(static_cast<EGLDisplay>(display_), static_cast<EGLSurface>(draw_), static_cast<EGLSurface>(read_),
                   static_cast<EGLContext>(context_));
  else
    eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);  // none was current
}

CompatContext::~CompatContext() {
  // OpenCSG's names are this context's: freed with it current.
  if (eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context)) OpenCSG::freeResources();
  eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(state_->display, state_->context);
}

namespace {

// One mesh as an OpenCSG primitive, drawn by the fixed function from vertex buffers.
class MeshPrimitive final : public OpenCSG::Primitive {
 public:
  MeshPrimitive(const Mesh& m, unsigned convexity) : Primitive(OpenCSG::Intersection, convexity) {
    glGenBuffers(1, &vertices_);
    glBindBuffer(GL_ARRAY_BUFFER, vertices_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.positions.size() * sizeof(glm::vec3)), m.positions.data(),
                 GL_STATIC_DRAW);
    glGenBuffers(1, &indices_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.indices.size() * 4), m.indices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    count_ = static_cast<GLsizei>(m.indices.size());
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    setBoundingBox(lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
  }
  ~MeshPrimitive() override {
    glDeleteBuffers(1, &vertices_);
    glDeleteBuffers(1, &indices_);
  }
  MeshPrimitive(const MeshPrimitive&) = delete;
  MeshPrimitive& operator=(const MeshPrimitive&) = delete;

  void render() override {
    glBindVertexArray(0);  // the compatibility profile's default vertex array, not a host's
    glBindBuffer(GL_ARRAY_BUFFER, vertices_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, nullptr);
    glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
    glDisableClientState(GL_VERTEX_ARRAY);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  }

 private:
  GLuint vertices_ = 0, indices_ = 0;
  GLsizei count_ = 0;
};

}  // namespace

struct OpenCsgPeer::Gpu {
  std::vector<std::unique_ptr<MeshPrimitive>> primitives;
  Extent screen;
  GLuint framebuffer = 0, colour = 0, depth = 0;
};

OpenCsgPeer::OpenCsgPeer(const Scene& scene, std::vector<std::uint32_t> convexity, Extent screen)
    : gpu_(std::make_unique<Gpu>()) {
  if (convexity.size() != scene.meshes.size())
    throw std::invalid_argument("OpenCsgPeer: " + std::to_string(convexity.size()) + " convexities for " +
                                std::to_string(scene.meshes.size()) + " primitives");
  for (std::size_t i = 0; i < scene.meshes.size(); ++i)
    gpu_->primitives.push_back(std::make_unique<MeshPrimitive>(scene.meshes[i], convexity[i]));
  gpu_->screen = screen;
  glGenRenderbuffers(1, &gpu_->colour);
  glBindRenderbuffer(GL_RENDERBUFFER, gpu_->colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, static_cast<GLsizei>(screen.x), static_cast<GLsizei>(screen.y));
  glGenRenderbuffers(1, &gpu_->depth);
  glBindRenderbuffer(GL_RENDERBUFFER, gpu_->depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, static_cast<GLsizei>(screen.x), static_cast<GLsizei>(screen.y));
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glGenFramebuffers(1, &gpu_->framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, gpu_->framebuffer);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, gpu_->colour);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, gpu_->depth);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) {
    glDeleteFramebuffers(1, &gpu_->framebuffer);
    glDeleteRenderbuffers(1, &gpu_->colour);
    glDeleteRenderbuffers(1, &gpu_->depth);
    throw std::runtime_error("OpenCsgPeer: the framebuffer " + screen.str() + " is not complete");
  }
}

OpenCsgPeer::~OpenCsgPeer() {
  glDeleteFramebuffers(1, &gpu_->framebuffer);
  glDeleteRenderbuffers(1, &gpu_->colour);
  glDeleteRenderbuffers(1, &gpu_->depth);
}

OpenCsgRender OpenCsgPeer::render(const std::vector<CsgProduct>& products, const Camera& camera,
                                  const OpenCsgMethod& method) {
  const Extent s = gpu_->screen;
  glBindFramebuffer(GL_FRAMEBUFFER, gpu_->framebuffer);
  glViewport(0, 0, static_cast<GLsizei>(s.x), static_cast<GLsizei>(s.y));
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixf(glm::value_ptr(camera.projection));
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixf(glm::value_ptr(camera.view));
  glDisable(GL_CULL_FACE);
  glDisable(GL_LIGHTING);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glClearColor(0, 0, 0, 0);
  glClearDepth(1.0);
  glClearStencil(0);
  OpenCSG::setOption(OpenCSG::AlgorithmSetting,
                     method.algorithm == OpenCsgAlgorithm::Goldfeather ? OpenCSG::Goldfeather : OpenCSG::SCS);
  OpenCSG::setOption(OpenCSG::DepthComplexitySetting, method.occlusion_queries ? OpenCSG::OcclusionQuery
                                                                                : OpenCSG::NoDepthComplexitySampling);
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  for (const CsgProduct& p : products) {
    std::vector<OpenCSG::Primitive*> list;
    for (std::uint32_t i : p.intersected) {
      gpu_->primitives.at(i)->setOperation(OpenCSG::Intersection);
      list.push_back(gpu_->primitives[i].get());
    }
    for (std::uint32_t i : p.subtracted) {
      gpu_->primitives.at(i)->setOperation(OpenCSG::Subtraction);
      list.push_back(gpu_->primitives[i].get());
    }
    OpenCSG::render(list);
    // Shading: each primitive's surface where it is the product's visible
    // one, in a colour that names it (index + 1).
    glDepthFunc(GL_EQUAL);
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::uint32_t index = k < p.intersected.size() ? p.intersected[k] : p.subtracted[k - p.intersected.size()];
      const std::uint32_t id = index + 1;
      glColor4ub(static_cast<GLubyte>(id & 0xff), static_cast<GLubyte>((id >> 8) & 0xff),
                 static_cast<GLubyte>((id >> 16) & 0xff), 255);
      list[k]->render();
    }
    glDepthFunc(GL_LESS);
  }
  glFinish();
  OpenCsgRender r;
  r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::vector<std::uint8_t> rgba(4 * s.area());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, static_cast<GLsizei>(s.x), static_cast<GLsizei>(s.y), GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  r.primitive.resize(s.area());
  for (std::size_t i = 0; i < r.primitive.size(); ++i) {
    const std::uint32_t id = rgba[4 * i] | (rgba[4 * i + 1] << 8) | (rgba[4 * i + 2] << 16);
    r.primitive[i] = static_cast<std::int32_t>(id) - 1;
  }
  return r;
}

}  // namespace habuffer::peers
