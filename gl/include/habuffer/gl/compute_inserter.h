// The GPU path's compute entry: the HA-buffer's table, max-age table and
// offsets in shader storage buffers, and a compute shader (the shared GLSL
// insert) that inserts a fragment stream held in a buffer. Needs a current
// OpenGL 4.5 core context; restores the GL state it touches (current program
// and shader-storage bindings 0-5) after every call.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "habuffer/buffer_config.h"
#include "habuffer/fragment.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/offset_sequence.h"

namespace habuffer::gl {

class ComputeInserter {
 public:
  // Throws GlError for a layout the mode cannot hold or a table too large for
  // 32-bit slot indices, and on shader errors (with the log).
  ComputeInserter(const BufferConfig& config, const OffsetSequence& offsets, AtomicMode mode);
  ~ComputeInserter();
  ComputeInserter(const ComputeInserter&) = delete;
  ComputeInserter& operator=(const ComputeInserter&) = delete;

  // Inserts into the current table (clear() first for a new frame).
  Counters insert(std::span<const Fragment> fragments);
  void clear();
  // Slots widened to 64 bits (L32 records in the low half).
  [[nodiscard]] std::vector<std::uint64_t> read_table() const;
  [[nodiscard]] std::vector<std::uint32_t> read_max_age() const;

 private:
  BufferConfig config_;
  std::uint32_t cells_ = 0;
  ShaderProgram program_;
  std::uint32_t word_bytes_ = 4;
  unsigned table_ = 0, max_age_ = 0, offsets_ = 0, fragments_ = 0, counters_ = 0, locks_ = 0;
};

}  // namespace habuffer::gl
