// Helpers of the GL test files: one headless context per process and the
// CPU-side twin of a GPU buffer.
#pragma once

#include <epoxy/gl.h>

#include <map>
#include <span>
#include <utility>
#include <vector>

#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "test_support.h"

namespace habuffer::test {

inline gl::EglContext& gl_context() {
  static gl::EglContext ctx;  // one per process: llvmpipe contexts are costly
  ctx.make_current();
  return ctx;
}

inline OffsetSource random_offsets(std::uint64_t seed) {
  OffsetSource s;
  s.generator = OffsetGenerator::Random;
  s.seed = seed;
  return s;
}

// Binding points a host might choose, away from the defaults, each
// technique's own buffers at points of their own (not the HA-buffer's).
inline gl::GlBindings host_bindings() {
  gl::GlBindings b;
  b.table = 7;
  b.max_age = 8;
  b.offsets = 9;
  b.heads = 4;
  b.nodes = 5;
  b.links = 6;
  b.counts = 5;
  b.layers = 6;
  b.slots = 2;
  b.occupancy = 4;
  b.limits = 6;
  b.accum = 6;
  b.revealage = 2;
  b.counters = 10;
  b.locks = 11;
  b.capture = 12;
  b.stream = 13;
  b.deferred = 14;
  b.saturation = 15;
  b.params = 3;
  return b;
}

// The stream reordered into waves that hold each pixel at most once, every
// pixel's fragments in their order, and where the waves end: inserted as
// ComputeInserter chunks, a GPU of any width inserts it as the CPU path does
// serially (no two calls of one pixel run at once).
inline std::pair<std::vector<Fragment>, std::vector<std::size_t>> pixel_waves(std::span<const Fragment> stream) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> seen;
  std::vector<std::vector<Fragment>> waves;
  for (const Fragment& f : stream) {
    const std::uint32_t wave = seen[{f.x, f.y}]++;
    if (wave >= waves.size()) waves.resize(wave + 1);
    waves[wave].push_back(f);
  }
  std::pair<std::vector<Fragment>, std::vector<std::size_t>> out;
  for (const auto& w : waves) {
    out.first.insert(out.first.end(), w.begin(), w.end());
    out.second.push_back(out.first.size());
  }
  return out;
}

inline Layout layout_of(gl::AtomicMode mode) { return mode == gl::AtomicMode::Native32 ? Layout::L32 : Layout::L64; }

// The CPU path's buffer for the GPU buffer's current table and offsets, fed `fragments`.
inline HaBuffer cpu_twin(const gl::GlHaBuffer& gpu, std::span<const Fragment> fragments) {
  HaBuffer cpu(gpu.config(), gpu.offsets());
  cpu.insert(fragments);
  return cpu;
}

// The resolve pass into an RGBA32F texture, read back row-major.
inline std::vector<glm::vec4> resolve_to_image(gl::GlFrameDriver& gpu, glm::vec3 background,
                                               gl::PassTiming* timing = nullptr) {
  const Extent screen = gpu.screen();
  GLuint texture = 0, framebuffer = 0;
  GLint previous = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, static_cast<GLsizei>(screen.x), static_cast<GLsizei>(screen.y));
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  const gl::PassTiming t = gpu.resolve(background);
  if (timing != nullptr) *timing = t;
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous));
  std::vector<glm::vec4> image(screen.area());
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(image.size() * sizeof(glm::vec4)), image.data());
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(1, &texture);
  return image;
}

}  // namespace habuffer::test
