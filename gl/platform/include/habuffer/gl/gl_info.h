/// @file
/// What the current GL context offers the GPU path, and which atomic modes of
/// the HA-buffer it can run.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "habuffer/record_layout.h"

namespace habuffer::gl {

/// How the GPU path raises slots by atomicMax; it fixes the record layout.
enum class AtomicMode {
  Native32,    ///< L32 records, atomicMax on uint
  Native64,    ///< L64 records, atomicMax on uint64_t (GL_NV_shader_atomic_int64)
  Emulated64,  ///< L64 records on drivers without 64-bit atomics (per-slot lock from 32-bit atomics)
};

/// "native32", "native64" or "emulated64".
std::string to_string(AtomicMode mode);

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

/// Modes this build can run on this context, in order of preference.
std::vector<AtomicMode> runnable_atomic_modes(const GlInfo& info);

/// The mode named by the environment variable HABUFFER_ATOMIC_MODE (native32,
/// native64 or emulated64), for tests and benchmarks that compare modes on one
/// GPU (emulated64 forced on a GPU with 64-bit atomics); none when unset.
/// Throws GlError naming the variable for any other value.
std::optional<AtomicMode> atomic_mode_override();

/// The mode the library runs a layout in: the override when it holds the
/// layout (native32 for L32; native64 or emulated64 for L64); else L32
/// native32, L64 native64 where the driver has 64-bit atomics, else
/// emulated64; none without 64-bit types. Throws GlError when the override
/// cannot run here or cannot hold the layout (native32 forced for L64),
/// naming the variable, the mode and the layout; a 64-bit mode forced beside
/// L32 (whose one mode is native32) is warned about once (log_once), never
/// replaced silently.
std::optional<AtomicMode> chosen_atomic_mode(const GlInfo& info, Layout layout);

}  // namespace habuffer::gl
