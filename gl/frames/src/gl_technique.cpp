#include "habuffer/gl/gl_technique.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "habuffer/gl/gl_error.h"

namespace habuffer::gl {

GlTechnique::GlTechnique(Technique technique, AtomicMode mode, const GlBindings& bindings, Extent screen,
                         std::uint32_t samples)
    : context_("making a GPU container"),
      technique_(technique),
      mode_(mode),
      bindings_(bindings),
      screen_(screen),
      samples_(samples) {
  // Before any container compiles a shader with them: a point beyond the
  // context's limits is one line naming it, not a compiler's log.
  bindings_.validate();
}

GlTechnique::~GlTechnique() = default;

std::string GlTechnique::module_source(ShaderStage stage, std::string_view header) const {
  return technique_module(technique_, mode_, bindings_, stage, header);
}

void GlTechnique::resize_screen(Extent screen) {
  if (screen.area() == 0)
    throw std::invalid_argument("screen size " + screen.str() + " is empty (the container stays at " + screen_.str() + ")");
  check_viewport_fits(screen);
  if (screen == screen_) return;
  change_screen(screen);
  screen_ = screen;
}

unsigned GlTechnique::gather_framebuffer() const {
  for (const GlPass& p : passes_)
    if (p.stage == GlPassStage::Gather && p.framebuffer != 0) return p.framebuffer;
  return 0;
}

void GlTechnique::gathered(std::span<const std::uint32_t>, FrameReport&) {}

void check_atomic_mode(AtomicMode mode, Layout layout) {
  if ((mode == AtomicMode::Native32) != (layout == Layout::L32))
    throw GlError("atomic mode " + to_string(mode) + " does not hold " + to_string(layout) + " records");
  if (mode == AtomicMode::Native32) return;
  const GlInfo info = query_gl_info();
  if (!info.int64_types)
    throw GlError("atomic mode " + to_string(mode) + " needs 64-bit shader types (GL_ARB_gpu_shader_int64)");
  if (mode == AtomicMode::Native64 && !info.atomic_int64)
    throw GlError("atomic mode native64 needs 64-bit shader atomics (GL_NV_shader_atomic_int64)");
}

std::uint64_t max_storage_bytes() {
  GLint64 bytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
  return static_cast<std::uint64_t>(bytes);
}

void check_storage_fits(std::uint64_t bytes, const std::string& what) {
  if (bytes > max_storage_bytes())
    throw GlError(what + " needs " + std::to_string(bytes) + " bytes, this OpenGL allows " +
                  std::to_string(max_storage_bytes()) + " per shader-storage buffer");
}

MultisampleLimits multisample_limits() {
  MultisampleLimits m;
  m.largest = INT32_MAX;
  const auto lower = [&](GLint value, const char* what) {
    if (value < m.largest) {
      m.largest = value;
      m.limited_by = what;
    }
  };
  const std::pair<GLenum, const char*> limits[] = {{GL_MAX_SAMPLES, "GL_MAX_SAMPLES"},
                                                   {GL_MAX_COLOR_TEXTURE_SAMPLES, "GL_MAX_COLOR_TEXTURE_SAMPLES"},
                                                   {GL_MAX_DEPTH_TEXTURE_SAMPLES, "GL_MAX_DEPTH_TEXTURE_SAMPLES"},
                                                   {GL_MAX_FRAMEBUFFER_SAMPLES, "GL_MAX_FRAMEBUFFER_SAMPLES"}};
  for (const auto& [e, what] : limits) {
    GLint v = 0;
    glGetIntegerv(e, &v);
    lower(v, what);
  }
  // Per format, the counts it holds (GL_SAMPLES, largest first): a count
  // every format a host's passes use holds, up to the limits.
  const GLenum formats[] = {GL_RGBA32F, GL_R32F, GL_DEPTH_COMPONENT32F};
  std::vector<std::vector<GLint>> held;
  for (GLenum format : formats) {
    GLint n = 0;
    glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, format, GL_NUM_SAMPLE_COUNTS, 1, &n);
    std::vector<GLint> counts(static_cast<std::size_t>(std::max(n, 0)));
    if (n > 0) glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, format, GL_SAMPLES, n, counts.data());
    held.push_back(std::move(counts));
  }
  for (GLint c : held.front()) {
    if (c < 2 || c > m.largest) continue;
    if (std::all_of(held.begin(), held.end(),
                    [&](const std::vector<GLint>& h) { return std::find(h.begin(), h.end(), c) != h.end(); }))
      m.counts.push_back(static_cast<std::uint32_t>(c));
  }
  std::sort(m.counts.begin(), m.counts.end());
  return m;
}

void check_samples_fit(std::uint32_t samples) {
  if (samples <= 1) return;
  const MultisampleLimits m = multisample_limits();
  if (samples > static_cast<std::uint32_t>(std::max(m.largest, 0)))
    throw GlError("--samples " + std::to_string(samples) + " is beyond this OpenGL's multisampled images: at most " +
                  std::to_string(std::max(m.largest, 1)) + " samples a pixel (" + m.limited_by + ")");
  if (std::find(m.counts.begin(), m.counts.end(), samples) == m.counts.end()) {
    std::string counts;
    for (std::uint32_t c : m.counts) counts += (counts.empty() ? "" : ", ") + std::to_string(c);
    throw GlError("--samples " + std::to_string(samples) + ": this OpenGL makes multisampled float images of " +
                  (counts.empty() ? std::string("no other count") : counts) +
                  " samples a pixel only (a count it rounds up would give masks the buffer cannot name): use " +
                  (counts.empty() ? std::string("--samples 1") : "one of those"));
  }
}

void check_viewport_fits(Extent screen) {
  GLint viewport[2] = {};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  if (screen.x > static_cast<std::uint32_t>(viewport[0]) || screen.y > static_cast<std::uint32_t>(viewport[1]))
    throw GlError("screen " + screen.str() + " exceeds this OpenGL's largest viewport " + std::to_string(viewport[0]) +
                  "x" + std::to_string(viewport[1]));
}

}  // namespace habuffer::gl
