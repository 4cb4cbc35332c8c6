// Embedding that a real engine survives (issue 35): an automatic container
// sized from a counting gather before its first frame and adapted after;
// EGL displays and GL state that belong to the host; misuse (no context,
// another context, a context gone, GL below 4.5) that fails in one line
// instead of aborting, hanging or touching another context's objects.
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "habuffer/fragment_streams.h"
#include "habuffer/gl/gl_context.h"
#include "habuffer/gl/gl_error.h"

namespace habuffer {
namespace {

std::vector<Fragment> stream(Extent screen, std::uint64_t count, std::uint64_t seed) {
  StreamOptions so;
  so.count = count;
  so.seed = seed;
  return make_stream(screen, so);
}

gl::AtomicMode any_mode() { return gl::runnable_atomic_modes(gl::query_gl_info()).back(); }

// An automatic HA-buffer (no table given), default frame options.
std::unique_ptr<gl::GlHaBuffer> automatic_buffer(Extent screen, gl::AtomicMode mode) {
  BufferConfig c;
  c.screen = screen;
  c.layout = test::layout_of(mode);
  return std::make_unique<gl::GlHaBuffer>(c, test::random_offsets(3), mode);
}
std::unique_ptr<gl::GlHaBuffer> automatic_buffer(Extent screen) { return automatic_buffer(screen, any_mode()); }

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const gl::GlError& e) {
    return e.what();
  }
  return "(no GlError)";
}

// Frames of growing, then shrinking depth through a default-configured
// driver: the first is counted (and only the first), sized by SPEC 8's
// first table and lossless in one gather; a deeper frame stays lossless
// (lossless growth is the automatic default); shallower frames shrink the
// table by the 80/30 rule, every frame lossless.
TEST(GlEmbedding, ADefaultDriverIsLosslessFromItsFirstFrameAndFollowsGrowingAndShrinkingDepth) {
  test::gl_context();
  const Extent screen{48, 40};
  auto gpu = automatic_buffer(screen);
  EXPECT_TRUE(gpu->counts_next_frame());
  EXPECT_EQ(*gpu->options().max_attempts, gl::GlFrameOptions::kAutomaticAttempts);
  gl::ComputeInserter inserter(*gpu);
  const std::uint64_t first = 6 * screen.area();
  const gl::FrameReport r0 = inserter.insert(stream(screen, first, 1));
  ASSERT_TRUE(r0.counted_fragments.has_value());
  EXPECT_EQ(*r0.counted_fragments, first);
  EXPECT_TRUE(r0.lossless());
  EXPECT_EQ(r0.attempts.size(), 1u);
  EXPECT_EQ(gpu->table(), ResizePolicy{}.initial_table(screen, first));
  std::uint64_t largest = gpu->table().area();
  for (std::uint64_t k = 1; k <= 3; ++k) {  // three times as deep
    const gl::FrameReport r = inserter.insert(stream(screen, 3 * first, 10 + k));
    EXPECT_FALSE(r.counted_fragments.has_value());
    EXPECT_TRUE(r.lossless()) << "frame " << k;
    largest = std::max<std::uint64_t>(largest, gpu->table().area());
  }
  EXPECT_GT(largest, ResizePolicy{}.initial_table(screen, first).area());
  for (std::uint64_t k = 0; k < 8; ++k) {  // a tenth of it
    const gl::FrameReport r = inserter.insert(stream(screen, first / 5, 20 + k));
    EXPECT_TRUE(r.lossless()) << "shallow frame " << k;
  }
  EXPECT_LT(gpu->table().area(), largest);
}

// A window resize counts the new screen's first frame again.
TEST(GlEmbedding, AnAutomaticContainerIsCountedAgainAfterAScreenResize) {
  test::gl_context();
  auto gpu = automatic_buffer({32, 32});
  gl::ComputeInserter inserter(*gpu);
  EXPECT_TRUE(inserter.insert(stream({32, 32}, 4000, 2)).counted_fragments.has_value());
  EXPECT_FALSE(gpu->counts_next_frame());
  gpu->resize_screen({40, 24});
  EXPECT_TRUE(gpu->counts_next_frame());
  const gl::FrameReport r = inserter.insert(stream({40, 24}, 5000, 3));
  ASSERT_TRUE(r.counted_fragments.has_value());
  EXPECT_EQ(*r.counted_fragments, 5000u);
  EXPECT_TRUE(r.lossless());
  // A host that sizes the table itself saves the count.
  auto sized = automatic_buffer({32, 32});
  sized->resize({64, 64});
  EXPECT_FALSE(sized->counts_next_frame());
  // A container of a given size is never counted, and refuses size_for.
  BufferConfig c;
  c.screen = {32, 32};
  c.table = {40, 40};
  c.layout = test::layout_of(any_mode());
  gl::GlHaBuffer given(c, test::random_offsets(3), any_mode());
  EXPECT_FALSE(given.counts_next_frame());
  EXPECT_THROW(given.size_for(100), std::invalid_argument);
}

// A host's unpack state (skips, row length, alignment, an unpack buffer)
// reaches none of the library's buffer clears: the tallies and the stored
// records are those of a frame without it, and the state is the host's after.
TEST(GlEmbedding, TheHostsUnpackStateReachesNoneOfTheLibrarysClears) {
  test::gl_context();
  const Extent screen{32, 24};
  const std::vector<Fragment> f = stream(screen, 3000, 5);
  std::uint64_t stored_plain = 0;
  {
    auto gpu = automatic_buffer(screen);
    gl::ComputeInserter inserter(*gpu);
    for (int k = 0; k < 2; ++k) stored_plain = inserter.insert(f).counters.stored();
  }
  GLuint unpack = 0;
  glCreateBuffers(1, &unpack);
  glNamedBufferData(unpack, 4096, nullptr, GL_STATIC_DRAW);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, unpack);
  glPixelStorei(GL_UNPACK_SKIP_ROWS, 3);
  glPixelStorei(GL_UNPACK_SKIP_PIXELS, 5);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  {
    auto gpu = automatic_buffer(screen);
    gl::ComputeInserter inserter(*gpu);
    for (int k = 0; k < 2; ++k) {
      const gl::FrameReport r = inserter.insert(f);
      EXPECT_EQ(r.counters.fragments, f.size()) << "frame " << k;
      EXPECT_TRUE(r.lossless());
      EXPECT_EQ(r.counters.stored(), stored_plain);
    }
  }
  GLint v = 0;
  glGetIntegerv(GL_UNPACK_SKIP_ROWS, &v);
  EXPECT_EQ(v, 3);
  glGetIntegerv(GL_UNPACK_SKIP_PIXELS, &v);
  EXPECT_EQ(v, 5);
  glGetIntegerv(GL_UNPACK_ROW_LENGTH, &v);
  EXPECT_EQ(v, 7);
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &v);
  EXPECT_EQ(v, 1);
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &v);
  EXPECT_EQ(v, static_cast<GLint>(unpack));
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  for (GLenum p : {GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_ROW_LENGTH}) glPixelStorei(p, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glDeleteBuffers(1, &unpack);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// Inside every gather (the counting one, the first frame's, a later frame's
// after the clear pass and the timers) the host finds its query buffer bound.
TEST(GlEmbedding, TheGatherSeesTheHostsQueryBufferBinding) {
  test::gl_context();
  const Extent screen{24, 24};
  auto gpu = automatic_buffer(screen);
  gl::ComputeInserter inserter(*gpu);
  inserter.upload(stream(screen, 1500, 7));
  GLuint query_buffer = 0;
  glCreateBuffers(1, &query_buffer);
  glNamedBufferData(query_buffer, 64, nullptr, GL_STATIC_DRAW);
  glBindBuffer(GL_QUERY_BUFFER, query_buffer);
  std::vector<GLint> seen;
  for (int k = 0; k < 3; ++k) {
    const gl::FrameReport r = gpu->frame([&] {
      GLint bound = 0;
      glGetIntegerv(GL_QUERY_BUFFER_BINDING, &bound);
      seen.push_back(bound);
      inserter.dispatch();
    });
    EXPECT_TRUE(r.lossless());
  }
  ASSERT_GE(seen.size(), 4u);  // the counting gather and three frames' gathers
  for (GLint b : seen) EXPECT_EQ(b, static_cast<GLint>(query_buffer));
  GLint after = 0;
  glGetIntegerv(GL_QUERY_BUFFER_BINDING, &after);
  EXPECT_EQ(after, static_cast<GLint>(query_buffer));
  glBindBuffer(GL_QUERY_BUFFER, 0);
  glDeleteBuffers(1, &query_buffer);
}

// With no context current, or another one, every call that reaches GL is a
// one-line GlError (never an abort in libepoxy or a loop); making the
// object's context current again, it works.
TEST(GlEmbedding, CallsWithNoContextOrAnotherContextAreOneLineErrors) {
  gl::EglContext& mine = test::gl_context();
  const gl::AtomicMode mode = any_mode();
  auto gpu = automatic_buffer({16, 16}, mode);
  gl::ComputeInserter inserter(*gpu);
  inserter.upload(stream({16, 16}, 500, 9));
  const auto frame = [&] { (void)gpu->frame([&] { inserter.dispatch(); }); };
  mine.release_current();
  EXPECT_EQ(gl::current_context(), nullptr);
  for (const auto& [name, call] : std::vector<std::pair<std::string, std::function<void()>>>{
           {"frame", frame},
           {"resolve", [&] { (void)gpu->resolve(glm::vec3(0.0f)); }},
           {"resize_screen", [&] { gpu->resize_screen({8, 8}); }},
           {"bind", [&] { gpu->bind(); }},
           {"read_capture", [&] { (void)gpu->read_capture(); }},
           {"a new container", [&] { (void)automatic_buffer({8, 8}, mode); }},
           {"query_gl_info", [&] { (void)gl::query_gl_info(); }}}) {
    const std::string e = error_of(call);
    EXPECT_NE(e.find("no OpenGL context is current"), std::string::npos) << name << ": " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  {
    gl::EglContext other;  // current now
    const std::string e = error_of(frame);
    EXPECT_NE(e.find("not the one this object was made on"), std::string::npos) << e;
  }
  mine.make_current();
  EXPECT_TRUE(gpu->frame([&] { inserter.dispatch(); }).lossless());
}

// Destroyed while another context is current, library objects delete none
// of that context's objects (names are per context); destroyed after their
// own context is gone, they release nothing through GL and do not abort.
TEST(GlEmbedding, ObjectsDestroyedOffTheirContextTouchNoOtherContextsObjects) {
  gl::EglContext& mine = test::gl_context();
  auto gpu = automatic_buffer({16, 16});
  auto inserter = std::make_unique<gl::ComputeInserter>(*gpu);
  (void)inserter->insert(stream({16, 16}, 400, 4));
  {
    gl::EglContext other;
    std::array<GLuint, 128> names{};
    glCreateBuffers(static_cast<GLsizei>(names.size()), names.data());  // the same small names ours have
    inserter.reset();
    gpu.reset();
    for (GLuint n : names) EXPECT_TRUE(glIsBuffer(n)) << "buffer " << n << " of the other context was deleted";
    glDeleteBuffers(static_cast<GLsizei>(names.size()), names.data());
  }
  mine.make_current();
  {
    auto context = std::make_unique<gl::EglContext>();
    auto orphan = automatic_buffer({16, 16});
    (void)gl::ComputeInserter(*orphan).insert(stream({16, 16}, 300, 6));
    context.reset();  // the context goes first
    orphan.reset();   // then its objects: no GL call, no abort
  }
  mine.make_current();
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// A shader built from another driver's module (here: the same technique
// with another module variant) inserts nothing into this driver: its calls
// are counted and the frame is refused naming them; the driver's own
// shaders then work.
TEST(GlEmbedding, AShaderBuiltFromAnotherDriversModuleIsRefusedAtTheFirstFrame) {
  test::gl_context();
  const Extent screen{16, 16};
  auto mine = automatic_buffer(screen);
  BufferConfig c;
  c.screen = screen;
  c.layout = test::layout_of(any_mode());
  gl::GlFrameOptions o;
  o.module.count_writes = true;  // another module text, the same binding points
  gl::GlHaBuffer other(c, test::random_offsets(3), any_mode(), o);
  gl::ComputeInserter foreign(other);
  foreign.upload(stream(screen, 300, 8));
  const std::string e = error_of([&] { (void)mine->frame([&] { foreign.dispatch(); }); });
  EXPECT_NE(e.find("300 insert calls came from a shader built from another driver's module_source()"), std::string::npos)
      << e;
  gl::ComputeInserter own(*mine);
  EXPECT_TRUE(own.insert(stream(screen, 300, 8)).lossless());
}

// A host's EGL display and context, and two EglContexts of the library on
// the same device display, destroyed in every order: the display the host
// initialised is never terminated by the library, so every context left
// can still be made current and used.
TEST(GlEmbedding, LibraryContextsNeverTerminateTheHostsDisplayInAnyDestructionOrder) {
  // The library's choice of display (gl_context() is not made: the host initialises first).
  EGLDisplay display = EGL_NO_DISPLAY;
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count) && count > 0)
      display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
  }
  if (display == EGL_NO_DISPLAY)
    display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  ASSERT_NE(display, EGL_NO_DISPLAY);
  // In a run of the whole binary in one process (scripts/gpu_checks.sh) the
  // library's test context initialised the display first: then the host
  // must not terminate it either.
  const bool initialised_before = eglQueryString(display, EGL_VERSION) != nullptr;
  ASSERT_TRUE(eglInitialize(display, nullptr, nullptr));
  ASSERT_TRUE(eglBindAPI(EGL_OPENGL_API));
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  const auto usable = [&](EGLContext c) {
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) return false;
    const bool ok = glGetString(GL_VERSION) != nullptr;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    return ok;
  };
  std::array<int, 3> order{0, 1, 2};  // 0: the host's, 1 and 2: EglContexts
  do {
    EGLContext host = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    ASSERT_NE(host, EGL_NO_CONTEXT);
    std::unique_ptr<gl::EglContext> lib[2] = {std::make_unique<gl::EglContext>(), std::make_unique<gl::EglContext>()};
    bool alive[3] = {true, true, true};
    for (int who : order) {
      if (who == 0)
        eglDestroyContext(display, host);
      else
        lib[who - 1].reset();
      alive[who] = false;
      if (alive[0]) {
        EXPECT_TRUE(usable(host)) << "the host's context after destroying " << who;
      }
      for (int k = 0; k < 2; ++k) {
        if (!alive[k + 1]) continue;
        EXPECT_NO_THROW(lib[k]->make_current()) << "EglContext " << k;
        lib[k]->release_current();
      }
    }
  } while (std::next_permutation(order.begin(), order.end()));
  EXPECT_EQ(eglQueryString(display, EGL_VERSION) != nullptr, true) << "the host's display was terminated";
  if (!initialised_before) eglTerminate(display);
}

// A context below OpenGL 4.5 (Mesa's version override) is refused naming
// 4.5, before any shader fails to link.
TEST(GlEmbedding, AContextBelowOpenGl45IsRefusedNamingTheVersion) {
  struct Override {  // read by Mesa when a context is made; gone however the test ends
    Override() { setenv("MESA_GL_VERSION_OVERRIDE", "4.3", 1); }
    ~Override() { unsetenv("MESA_GL_VERSION_OVERRIDE"); }
  } override_version;
  EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) GTEST_SKIP() << "no Mesa surfaceless display";
  const bool initialised_before = eglQueryString(display, EGL_VERSION) != nullptr;
  if (!eglInitialize(display, nullptr, nullptr)) GTEST_SKIP() << "no Mesa surfaceless display";
  ASSERT_TRUE(eglBindAPI(EGL_OPENGL_API));
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext c = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (c == EGL_NO_CONTEXT) GTEST_SKIP() << "no 4.3 context";
  ASSERT_TRUE(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, c));
  if (epoxy_gl_version() >= 45) {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, c);
    GTEST_SKIP() << "the driver ignored MESA_GL_VERSION_OVERRIDE";
  }
  const std::string e = error_of([] { (void)automatic_buffer({8, 8}); });
  EXPECT_NE(e.find("OpenGL 4.5 core is needed"), std::string::npos) << e;
  EXPECT_NE(e.find("4.3"), std::string::npos) << e;
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, c);
  if (!initialised_before) eglTerminate(display);
}

}  // namespace
}  // namespace habuffer
