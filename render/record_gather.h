/// @file
/// One gather of L64 records into an HA-buffer sized from a counting pass,
/// for the render library's passes whose output is records (the voxelizer's
/// crossings, CSG's primitives): on the GPU path lossless (up to 16
/// gathers), on the CPU path the GPU only rasterizes and captures and the
/// CPU path's HA-buffer grows until nothing drops. Also the framebuffer
/// without attachments those passes draw into. Private to the render library.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "habuffer/buffer_config.h"
#include "habuffer/counters.h"
#include "habuffer/fragment_buffer.h"
#include "habuffer/record_layout.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/shader_program.h"

namespace habuffer {

/// Throws GlError "WHAT WxH exceeds this OpenGL's largest viewport AxB
/// (GL_MAX_VIEWPORT_DIMS)" (or framebuffer, texture, renderbuffer: the first
/// limit `screen` passes) unless every attachment and viewport of a pass of
/// that size can be made: checked before any GL object is, so a size too
/// large is one error naming the size, not the driver's GL_INVALID_VALUE
/// lines. `what` names the size ("csg: --size"). Needs a current context.
void check_screen_fits(Extent screen, const std::string& what);

/// A framebuffer with no attachment, of one size: the passes drawn into it
/// write no colour and no depth, only records or sample counts. Needs a
/// current OpenGL 4.5 context (check_screen_fits: GlError for a size it
/// cannot have); deletes the framebuffer when destroyed.
class EmptyFramebuffer {
 public:
  explicit EmptyFramebuffer(Extent size);
  ~EmptyFramebuffer();
  EmptyFramebuffer(const EmptyFramebuffer&) = delete;
  EmptyFramebuffer& operator=(const EmptyFramebuffer&) = delete;

  /// Binds it with its viewport, depth test, culling (both facings drawn)
  /// and blending off, runs `draw` with `program` in use, and unbinds both.
  void draw_with(const gl::ShaderProgram& program, const std::function<void()>& draw) const;

 private:
  Extent size_;
  unsigned framebuffer_ = 0;
};

/// What one gather gave.
struct RecordGather {
  RecordLayout layout{Layout::L64, HABUFFER_DEFAULT_AGE_BITS};  ///< the records' layout (their depth codes)
  std::unique_ptr<FragmentBuffer> buffer;  ///< the records: read back from the GPU, or the CPU path's build
  Counters counters;                       ///< of the final gather (or the CPU build's final attempt)
  std::uint32_t attempts = 0;              ///< gathers (GPU) or build attempts (CPU)
  std::uint64_t list_bytes = 0;            ///< GPU: the container's bytes; CPU: the memory model's
  Extent table;                            ///< the final table
};

/// How to draw one gather: the vertex shader, the GLSL appended to the
/// HA-buffer module's fragment source, the program's uniforms, and the draw calls.
struct GatherPass {
  std::string vertex_source;    ///< a whole vertex shader
  std::string fragment_source;  ///< after the module's fragment source (calls habuffer_insert)
  std::string name;             ///< names its programs and errors ("csg": "csg counting pass", "csg gather")
  std::function<void(const gl::ShaderProgram&)> prepare;  ///< sets the program's uniforms
  std::function<void(const gl::ShaderProgram&)> draw;     ///< draws with the program
};

/// The records of `pass` on a `screen` of pixels in an L64 HA-buffer sized
/// from a counting pass of the same draw (see the file comment). `cpu`
/// chooses the CPU path, on `threads`. Throws GlError when the context has
/// no 64-bit shader types; counts failures without throwing: each caller
/// names what a lost record means.
RecordGather gather_records(Extent screen, bool cpu, std::uint32_t threads, const GatherPass& pass);

}  // namespace habuffer
