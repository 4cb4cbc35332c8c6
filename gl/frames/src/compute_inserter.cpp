#include "habuffer/gl/compute_inserter.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "compute_grid.h"
#include "gl_state_guard.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {

namespace {

// The driver's module (its variant's defines included) with the entry's
// code. The blended baselines need the blender: their stream is drawn as points.
ShaderProgram entry_program(const GlFrameDriver& buffer) {
  const Technique t = buffer.technique().technique();
  if (stores_lists(t))
    return ShaderProgram::compute(buffer.module_source(ShaderStage::Compute) + kInsertStreamCompute,
                                  "insert compute shader");
  // The vertex stage takes the compute module for HaFragment and the parameters.
  return ShaderProgram::graphics(buffer.module_source(ShaderStage::Compute) + kPointStreamVertex,
                                 buffer.module_source(ShaderStage::Fragment) + kPointStreamFragment,
                                 to_string(t) + " insert points");
}

}  // namespace

ComputeInserter::ComputeInserter(GlFrameDriver& buffer, std::size_t max_chunk)
    : buffer_(buffer),
      program_(entry_program(buffer)),
      points_(!stores_lists(buffer.technique().technique())),
      max_chunk_(max_chunk) {
  if (points_) glCreateVertexArrays(1, &vertex_array_);
}

ComputeInserter::~ComputeInserter() {
  if (!made_on_.current()) return;  // not another context's names (gl_context.h)
  release();
  glDeleteVertexArrays(1, &vertex_array_);
}

void ComputeInserter::release() {
  for (const Chunk& c : chunks_) glDeleteBuffers(1, &c.buffer);
  chunks_.clear();
}

void ComputeInserter::upload(std::span<const Fragment> fragments, std::span<const std::size_t> chunk_ends) {
  const Extent screen = buffer_.screen();
  for (std::size_t i = 0; i < fragments.size(); ++i)
    if (fragments[i].x >= screen.x || fragments[i].y >= screen.y)
      throw GlError("fragment " + std::to_string(i) + " at (" + std::to_string(fragments[i].x) + ", " +
                    std::to_string(fragments[i].y) + ") lies outside screen " + screen.str());
  for (std::size_t k = 0; k < chunk_ends.size(); ++k)
    if (chunk_ends[k] > fragments.size() || (k > 0 && chunk_ends[k] < chunk_ends[k - 1]))
      throw GlError("chunk end " + std::to_string(k) + " (" + std::to_string(chunk_ends[k]) +
                    ") is not in order within the stream of " + std::to_string(fragments.size()));
  release();
  // Streams beyond one shader-storage buffer (128 MiB, 8 M fragments on
  // llvmpipe) go in several, dispatched one after the other.
  std::size_t per_chunk =
      std::min<std::size_t>(static_cast<std::size_t>(max_storage_bytes()) / sizeof(Fragment), std::size_t{1} << 26);
  if (max_chunk_ > 0) per_chunk = std::min(per_chunk, max_chunk_);
  std::size_t next_end = 0;
  for (std::size_t first = 0; first < fragments.size() || first == 0;) {
    while (next_end < chunk_ends.size() && chunk_ends[next_end] <= first) ++next_end;
    const std::size_t end = std::min({fragments.size(), first + per_chunk,
                                      next_end < chunk_ends.size() ? chunk_ends[next_end] : fragments.size()});
    const std::size_t n = end - first;
    chunks_.push_back({create_buffer(n * sizeof(Fragment), n > 0 ? fragments.data() + first : nullptr), n});
    if (fragments.empty()) break;
    first = end;
  }
}

void ComputeInserter::dispatch() const {
  glUseProgram(program_.id());
  if (points_) {
    // Inside the frame's gather: the driver bound the technique's framebuffer
    // and blend setup; the points cover one pixel each of a screen viewport.
    glBindVertexArray(vertex_array_);
    GlStateGuard::prepare_point_pass();  // the frame's guard restores the host's state
    GlStateGuard::set_viewport(static_cast<GLsizei>(buffer_.screen().x), static_cast<GLsizei>(buffer_.screen().y));
  }
  for (const Chunk& c : chunks_) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, buffer_.bindings().stream, c.buffer);
    if (points_) {
      glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(c.count));
    } else {
      program_.set("ha_stream_count", static_cast<unsigned>(c.count));
      dispatch_grid(c.count, 64);
      // Chunks run in stream order: the next sees every write of this one.
      if (&c != &chunks_.back()) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }
}

std::size_t ComputeInserter::uploaded() const {
  std::size_t n = 0;
  for (const Chunk& c : chunks_) n += c.count;
  return n;
}

FrameReport ComputeInserter::insert(std::span<const Fragment> fragments, std::span<const std::size_t> chunk_ends) {
  upload(fragments, chunk_ends);
  // frame() reconciles its tallies with the call count: every fragment ends counted.
  return buffer_.frame([&] { dispatch(); }, [&] { return std::uint64_t{uploaded()}; });
}

}  // namespace habuffer::gl
