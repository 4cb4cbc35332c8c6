/// @file
/// The spatial hash (habuffer/spatial/spatial_hash.h) on the GPU: the same
/// insert and lookup (core/include/habuffer/spatial/sh_spatial.glsl) run by
/// compute shaders, one record or query per invocation, so the table the GPU
/// builds is the CPU's bit for bit (the deferred-acceptance argument of
/// docs/spec-notes.md, "The spatial hash"; tested).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/spatial/spatial_hash.h"

namespace habuffer::gl {

/// One table on the GPU of the current context. Its buffers go to the
/// points of `GlBindings` (table, max_age, offsets, locks; the passes'
/// stream, deferred, capture and counters), and a GlStateGuard puts the
/// host's bindings and program back before each call returns.
class GlSpatialHash {
 public:
  /// Uploads `table`: its parameters, offsets, slots and max-age cells.
  /// Throws GlError when the context lacks 64-bit integers in shaders, or a
  /// buffer beyond the driver's shader-storage limit.
  explicit GlSpatialHash(const spatial::SpatialHash& table, const GlBindings& bindings = {});

  /// A key that failed (its record carried past AMAX ages or the iteration
  /// limit): the caller grows the table and inserts it again.
  struct Dropped {
    glm::uvec3 key;
    std::uint32_t stored;  ///< the value as stored (the rule's encoding)
  };
  /// Inserts each key with its stored value (the rule's encoding: Max and
  /// Min only; keys in the domain). Calls cut short (a busy emulated lock,
  /// the driver's loop budget) are resumed by further passes until none is
  /// left. Returns the counters; failed calls' records go to `dropped`.
  spatial::InsertReport insert(std::span<const glm::uvec3> keys, std::span<const std::uint32_t> stored,
                               std::vector<Dropped>& dropped);
  /// Batched lookup: found[i] and the stored value (0 where absent) of keys[i]
  /// (keys in the domain). Returns the keys found.
  std::uint64_t find(std::span<const glm::uvec3> keys, std::span<std::uint32_t> stored,
                     std::span<std::uint8_t> found) const;

  /// Empties the table on the GPU (its size kept).
  void clear();
  /// GPU time of the last insert's or find's passes (GPU timestamps around
  /// the dispatches: no transfers), in milliseconds; 0 on Mesa's software
  /// rasterizers, whose timestamps time the submission only.
  [[nodiscard]] double gpu_ms() const { return gpu_ms_; }

  /// The slots and max-age cells read back.
  [[nodiscard]] std::vector<std::uint64_t> slots() const;
  [[nodiscard]] std::vector<std::uint32_t> max_age() const;
  /// native64 or emulated64.
  [[nodiscard]] AtomicMode mode() const { return mode_; }
  /// Resume passes the last insert needed (0: none was cut short).
  [[nodiscard]] std::uint32_t resume_passes() const { return resume_passes_; }

 private:
  // The constructor's work on the context's info, queried once.
  GlSpatialHash(const spatial::SpatialHash& table, const GlBindings& bindings, const GlInfo& info);
  void bind_table() const;  // the table's buffers at their points
  GlBindings bindings_;
  spatial::SpatialKernelParams params_;
  spatial::FoldedDomain fold_;
  AtomicMode mode_;
  bool timed_;  // GL_TIME_ELAPSED times the shaders (not on Mesa's software rasterizers)
  ShaderProgram insert_, find_;
  std::uint64_t slot_count_ = 0, cell_count_ = 0;
  GlStorage table_, max_age_, offsets_, locks_;
  std::uint32_t resume_passes_ = 0;
  mutable double gpu_ms_ = 0.0;
};

/// Inserts keys into `table` on the GPU of the current context (rules Max and
/// Min: First and Last order a batch, which concurrent GPU calls do not),
/// then takes the GPU's table back into `table` (checked as a loaded table
/// is). Adaptive growth before the insert, and lossless growth for calls that
/// failed, rebuild on the CPU (the same table: the build does not depend on
/// order). Throws std::invalid_argument for First or Last, a key outside the
/// domain or sizes that differ.
spatial::InsertReport gl_insert(spatial::SpatialHash& table, std::span<const glm::uvec3> keys,
                                std::span<const std::uint32_t> values = {});

}  // namespace habuffer::gl
