#include "habuffer/render/render_job.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_ha_buffer.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/fragment_streams.h"
#include "habuffer/render/scene_renderer.h"

namespace habuffer {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

bool automatic_table(const RenderSettings& s) { return s.config.table.area() == 0; }

std::uint32_t largest(std::span<const std::uint32_t> v) {
  return v.empty() ? 0u : *std::max_element(v.begin(), v.end());
}

void validate(const RenderSettings& s) {
  s.config.validate();
  s.policy.validate();
  if (s.frames == 0) throw std::invalid_argument("--frames must be at least 1");
  if (s.max_attempts == 0) throw std::invalid_argument("--max-attempts must be at least 1");
}

// An automatic table's first size: the fragments at the middle of the
// policy's band of loads (SPEC 8 keeps it there afterwards), at least the
// screen, and no larger than the GPU path can hold.
Extent initial_table(const RenderSettings& s, std::uint64_t fragments) {
  const double target = (s.policy.grow_at + s.policy.shrink_at) / 2.0;
  return table_for_load(s.config.screen, fragments, target);
}

// The largest table up to `wanted` (same aspect) the context holds.
Extent fit_gpu_table(const gl::GlHaBuffer& ha, Extent wanted) {
  GLint64 max_bytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_bytes);
  const std::uint64_t max_slots = static_cast<std::uint64_t>(max_bytes) / ha.config().record_layout().word_bytes();
  if (wanted.area() <= max_slots) return wanted;
  const double scale = std::sqrt(static_cast<double>(max_slots) / static_cast<double>(wanted.area()));
  const Extent screen = ha.config().screen;
  return {std::max(screen.x, static_cast<std::uint32_t>(wanted.x * scale)),
          std::max(screen.y, static_cast<std::uint32_t>(wanted.y * scale))};
}

gl::GlFrameOptions frame_options(const RenderSettings& s) {
  gl::GlFrameOptions o;
  const bool gpu = s.path == RenderPath::Gl;  // the CPU path only captures: its GPU table stays unused
  o.adaptive = gpu && automatic_table(s);
  o.policy = s.policy;
  o.max_attempts = gpu && (automatic_table(s) || s.lossless) ? s.max_attempts : 1;
  o.capture = s.keep_fragments || !gpu;
  o.capture_only = !gpu;
  o.count_writes = gpu;
  return o;
}

// The GPU buffer's configuration: the CPU path's is screen-sized (it only captures).
BufferConfig gpu_config(const RenderSettings& s) {
  BufferConfig c = s.config;
  if (s.path == RenderPath::Cpu) c.table = c.screen;
  return c;
}

// An RGBA32F target for the resolve pass, read back as an Image.
class ResolveTarget {
 public:
  explicit ResolveTarget(Extent size) : size_(size) {
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA32F, static_cast<GLsizei>(size.x), static_cast<GLsizei>(size.y));
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, texture_, 0);
  }
  ~ResolveTarget() {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &texture_);
  }
  ResolveTarget(const ResolveTarget&) = delete;
  ResolveTarget& operator=(const ResolveTarget&) = delete;

  [[nodiscard]] unsigned framebuffer() const { return framebuffer_; }
  [[nodiscard]] Image read() const {
    Image image{size_, std::vector<glm::vec4>(size_.area())};
    glGetTextureImage(texture_, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(image.pixels.size() * sizeof(glm::vec4)),
                      image.pixels.data());
    return image;
  }

 private:
  Extent size_;
  unsigned texture_ = 0, framebuffer_ = 0;
};

std::vector<std::uint32_t> culled_per_pixel(const HaBuffer& like, std::span<const Fragment> fragments) {
  HaBuffer replay(BufferConfig(like.config()), like.offsets());
  std::vector<std::uint32_t> culled(like.screen().area(), 0);
  for (const Fragment& f : fragments)
    if (replay.insert_one(f) == HA_CULLED) ++culled[f.x + std::size_t{f.y} * like.screen().x];
  return culled;
}

void finish_stats(FrameStats& fs) {
  fs.load_factor = fs.table.area() > 0 ? static_cast<double>(fs.counters.stored()) / static_cast<double>(fs.table.area()) : 0.0;
}

// The CPU path's table for the next frame: auto sizing (SPEC 8, exact count,
// one frame of latency); a given table stays.
struct CpuTableState {
  Extent table;
  std::optional<std::uint64_t> previous_stored;
};

BuildResult build_on_cpu(const RenderSettings& s, CpuTableState& state, std::span<const Fragment> fragments,
                         FrameStats& fs) {
  if (automatic_table(s) && state.previous_stored) {
    const Extent next = s.policy.next(state.table, s.config.screen, *state.previous_stored);
    fs.resized = next != state.table;
    state.table = next;
  }
  BufferConfig c = s.config;
  c.table = state.table;
  InsertOptions options;
  options.threads = s.threads;
  const auto t0 = Clock::now();
  BuildResult b = build(c, s.offsets, fragments, options, s.policy,
                        automatic_table(s) || s.lossless ? s.max_attempts : 1);
  fs.gather_ms = ms_since(t0);
  state.table = b.buffer.table();
  state.previous_stored = b.counters.stored();
  fs.table = state.table;
  fs.attempts = static_cast<std::uint32_t>(b.attempts.size());
  fs.counters = b.counters;
  fs.max_age = largest(b.buffer.max_age().ages());
  return b;
}

}  // namespace

RenderResult render_scene(const Scene& scene, const RenderSettings& s) {
  validate(s);
  const Extent screen = s.config.screen;
  const gl::GlInfo info = gl::query_gl_info();
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(info, s.config.layout);
  if (!mode) throw gl::GlError("--layout 64 needs 64-bit shader types (GL_ARB_gpu_shader_int64), which this OpenGL lacks");
  gl::GlHaBuffer ha(gpu_config(s), s.offsets, *mode, frame_options(s));
  SceneRenderer renderer(scene, screen, ha);
  ResolveTarget target(screen);
  CpuTableState cpu{s.config.table_or_screen(), std::nullopt};
  std::optional<BuildResult> last_cpu;
  RenderResult result;
  for (std::uint32_t k = 0; k < s.frames; ++k) {
    const auto t0 = Clock::now();
    FrameStats fs;
    fs.index = k;
    fs.yaw = s.camera.yaw + 360.0f * static_cast<float>(k) / static_cast<float>(s.frames);
    CameraParams params = s.camera;
    params.yaw = fs.yaw;
    const Camera camera = frame_scene(scene, params, screen);
    renderer.draw_opaque(camera, s.background);
    if (k == 0) {
      ha.bind();  // the gather shader's uniform block, even though counting inserts nothing
      const std::uint64_t fragments = renderer.count_fragments(camera);
      if (fragments > UINT32_MAX)
        throw gl::GlError("a frame of " + std::to_string(fragments) +
                          " fragments overflows the GPU path's 32-bit counters: render a smaller view or fewer layers");
      if (automatic_table(s)) {
        // Size the first table from the count, so frame 0 need not fail its way up.
        const Extent first = initial_table(s, fragments);
        cpu.table = first;
        if (s.path == RenderPath::Gl) {
          const Extent fitted = fit_gpu_table(ha, first);
          result.growth_limited = result.growth_limited || fitted != first;
          ha.resize(fitted);
        }
      }
    }
    const gl::FrameReport report = ha.frame([&] { renderer.gather(camera); }, [&] { return renderer.inserted(); });
    fs.opaque_rejected = renderer.read_rejected();
    if (s.path == RenderPath::Gl) {
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.framebuffer());
      fs.resolve_ms = ha.resolve(s.background, renderer.opaque_colour_texture()).wall_ms;
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      fs.table = report.table;
      fs.resized = report.resized;
      fs.attempts = static_cast<std::uint32_t>(report.attempts.size());
      fs.counters = report.counters;
      fs.slot_writes = report.slot_writes;
      fs.deferred = report.deferred;
      fs.resume_rounds = report.resume_rounds;
      fs.resize_limited = report.resize_limited;
      fs.gather_ms = report.gather.wall_ms;
      fs.max_age = largest(ha.read_max_age());
      result.growth_limited = result.growth_limited || report.growth_limited;
    } else {
      const std::vector<Fragment> fragments = ha.read_capture();
      last_cpu.emplace(build_on_cpu(s, cpu, fragments, fs));
      const auto r0 = Clock::now();
      result.backgrounds = renderer.read_opaque_colour();
      const std::vector<glm::vec4> pixels = last_cpu->buffer.composite_image(result.backgrounds, s.threads);
      fs.resolve_ms = ms_since(r0);
      result.image = Image{screen, pixels};
      if (k + 1 == s.frames) result.fragments = fragments;
    }
    finish_stats(fs);
    fs.frame_ms = ms_since(t0);
    result.frames.push_back(fs);
    if (s.on_progress) s.on_progress(k + 1, s.frames);
  }
  result.pixel_fragments = renderer.read_pixel_fragments();
  if (s.path == RenderPath::Gl) {
    result.backgrounds = renderer.read_opaque_colour();  // the CPU path read them for its last composite
    result.image = target.read();
    result.pixel_culled = renderer.read_pixel_culled();
    if (s.keep_fragments) result.fragments = ha.read_capture();
    result.buffer.emplace(ha.config(), ha.offsets());
    result.buffer->import_state(ha.read_table(), ha.read_max_age());
    result.memory_bytes = ha.memory_bytes();
    result.device = "gl " + gl::to_string(*mode) + " on " + info.renderer;
  } else {
    if (s.per_pixel_culled) result.pixel_culled = culled_per_pixel(last_cpu->buffer, result.fragments);
    result.memory_bytes = last_cpu->buffer.memory_bytes();
    result.buffer.emplace(std::move(last_cpu->buffer));
    result.device = "cpu, fragments rasterized by gl (" + info.renderer + ")";
  }
  gl::check_gl_errors("rendering");
  return result;
}

RenderResult render_fragments(std::span<const Fragment> fragments, const RenderSettings& s) {
  validate(s);
  RenderResult result;
  CpuTableState cpu{automatic_table(s) ? initial_table(s, fragments.size()) : s.config.table, std::nullopt};
  FrameStats fs;
  const auto t0 = Clock::now();
  BuildResult b = build_on_cpu(s, cpu, fragments, fs);
  const auto r0 = Clock::now();
  result.backgrounds.assign(s.config.screen.area(), s.background);
  result.image = Image{s.config.screen, b.buffer.composite_image(result.backgrounds, s.threads)};
  fs.resolve_ms = ms_since(r0);
  finish_stats(fs);
  fs.frame_ms = ms_since(t0);
  result.frames.push_back(fs);
  result.pixel_fragments.assign(s.config.screen.area(), 0);
  for (const Fragment& f : fragments) ++result.pixel_fragments[f.x + std::size_t{f.y} * s.config.screen.x];
  if (s.per_pixel_culled) result.pixel_culled = culled_per_pixel(b.buffer, fragments);
  result.fragments.assign(fragments.begin(), fragments.end());
  result.memory_bytes = b.buffer.memory_bytes();
  result.buffer.emplace(std::move(b.buffer));
  result.device = "cpu";
  return result;
}

}  // namespace habuffer
