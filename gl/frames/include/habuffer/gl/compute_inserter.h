/// @file
/// The GPU path's compute entry: a compute shader that inserts a fragment
/// stream held in a buffer through the same habuffer_insert host fragment shaders
/// call (tests, sweeps and `build-lists --path gl` use it). For the blended
/// baselines (wboit, blend), whose insert needs the fixed-function blender,
/// the same stream is drawn as points instead, one per fragment in stream order.
#pragma once

#include <span>
#include <vector>

#include "habuffer/fragment.h"
#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/gl/gl_context.h"

namespace habuffer::gl {

/// The GPU path's compute entry for one frame driver: uploads a fragment stream
/// and inserts it through the same habuffer_insert host fragment shaders call.
class ComputeInserter {
 public:
  /// Compiles the entry for `buffer`'s atomic mode and binding points (throws
  /// GlError with the log on shader errors). `buffer` must outlive this.
  /// max_chunk: fragments per stream buffer (0: as many as one shader-storage
  /// buffer holds).
  explicit ComputeInserter(GlFrameDriver& buffer, std::size_t max_chunk = 0);
  /// Deletes the stream buffers.
  ~ComputeInserter();
  ComputeInserter(const ComputeInserter&) = delete;
  ComputeInserter& operator=(const ComputeInserter&) = delete;

  /// Uploads the stream (kept for later dispatches), in several buffers when
  /// it exceeds one, and also split at `chunk_ends` (increasing indices into
  /// the stream). Chunks are inserted in order, each after every write of
  /// the one before (a memory barrier between dispatches): with at most one
  /// fragment per pixel in each chunk, no two calls of one pixel run at once,
  /// whatever the GPU's width (the HA-buffer's evictions still move other
  /// pixels' records concurrently, and emulated64 resumes calls it cut short
  /// after the whole gather). Throws GlError
  /// naming the first fragment outside the screen, as the CPU path does, or
  /// chunk ends out of order.
  void upload(std::span<const Fragment> fragments, std::span<const std::size_t> chunk_ends = {});
  /// Fragments in the uploaded stream, over all its buffers.
  [[nodiscard]] std::size_t uploaded() const;
  /// Inserts the uploaded stream; call inside GlFrameDriver::frame's gather.
  void dispatch() const;
  /// One frame whose gather is the stream: upload, then buffer.frame(dispatch).
  FrameReport insert(std::span<const Fragment> fragments, std::span<const std::size_t> chunk_ends = {});

 private:
  GlFrameDriver& buffer_;
  ShaderProgram program_;
  bool points_ = false;         ///< the stream is drawn as points (the blended baselines)
  unsigned vertex_array_ = 0;   ///< the empty vertex array the point draw needs
  MadeOn made_on_;              ///< the context its names belong to
  struct Chunk {
    unsigned buffer;
    std::size_t count;
  };
  void release();
  std::vector<Chunk> chunks_;
  std::size_t max_chunk_ = 0;
};

}  // namespace habuffer::gl
