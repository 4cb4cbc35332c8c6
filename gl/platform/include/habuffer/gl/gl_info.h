/// @file
/// What the current GL context offers the GPU path, and which atomic modes of
/// the HA-buffer it can run.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "habuffer/atomic_mode.h"
#include "habuffer/record_layout.h"

namespace habuffer::gl {

/// The atomic modes are every GPU path's (habuffer/atomic_mode.h).
using habuffer::AtomicMode;
using habuffer::to_string;

/// What query_gl_info() read from the current context.
struct GlInfo {
  /// The strings GL_VENDOR, GL_RENDERER, GL_VERSION and
  /// GL_SHADING_LANGUAGE_VERSION (empty when missing).
  std::string vendor, renderer, version, glsl_version;
  bool int64_types = false;    ///< GL_ARB_gpu_shader_int64
  bool atomic_int64 = false;   ///< GL_NV_shader_atomic_int64
  bool khr_debug = false;  ///< GL_KHR_debug or GL 4.3
  bool occlusion_query2 = false;  ///< GL_ARB_occlusion_query2 or GL 3.3
  long long max_ssbo_bytes = 0;  ///< GL_MAX_SHADER_STORAGE_BLOCK_SIZE (bytes)
  /// GL_MAX_FRAMEBUFFER_WIDTH and GL_MAX_FRAMEBUFFER_HEIGHT (pixels).
  int max_framebuffer_width = 0, max_framebuffer_height = 0;
  int max_compute_work_groups_x = 0;  ///< GL_MAX_COMPUTE_WORK_GROUP_COUNT in x
  /// Mesa's software rasterizers (llvmpipe, softpipe, by GL_RENDERER): shaders
  /// run on the CPU. Their loop budget can end an insert call without an
  /// outcome (docs/spec-notes.md, "Loop budget"), and an atomic costs a
  /// locked read-modify-write of a CPU cache line.
  bool software_rasterizer = false;
};

/// Needs a current OpenGL 4.5 core context.
GlInfo query_gl_info();

/// What the context offers the atomic modes, in OpenGL's words.
AtomicSupport atomic_support(const GlInfo& info);
/// Modes this build can run on this context, in order of preference.
std::vector<AtomicMode> runnable_atomic_modes(const GlInfo& info);

/// atomic_mode_override() (habuffer/atomic_mode.h), its error a GlError.
std::optional<AtomicMode> atomic_mode_override();

/// The mode the library runs a layout in on this context: every path's rule
/// (habuffer::chosen_atomic_mode), its errors GlError, its warning through
/// log_once.
std::optional<AtomicMode> chosen_atomic_mode(const GlInfo& info, Layout layout);

}  // namespace habuffer::gl
