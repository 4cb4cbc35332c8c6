/// @file
/// The spatial hash (habuffer/spatial/spatial_hash.h) on the GPU: the same
/// insert and lookup (core/spatial/include/habuffer/spatial/sh_spatial.glsl) run by
/// compute shaders, one record or query per invocation, so the table the GPU
/// builds is the CPU's bit for bit (the deferred-acceptance argument of
/// docs/spec-notes.md, "The spatial hash"; tested).
///
/// Host shaders look the table up themselves: append spatial_lookup_part()
/// (or include the installed share/habuffer/glsl/spatial_lookup.glsl), call
///
///   bool habuffer_spatial_find(uvec3 key, out uint stored);
///   bool habuffer_spatial_find_value(uvec3 key, out uint value);
///
/// and bind the table with GlSpatialHash::bind_for_lookup() before the draw
/// or dispatch. The lookup is the library's find pass's own fold and probe
/// (gl/effects/shaders/spatial_keys.glsl, instantiated under the prefix sh_), so a
/// host shader answers as GlSpatialHash::find and the CPU table do.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/spatial/spatial_hash.h"

namespace habuffer::gl {

/// Where GlSpatialHash::bind_for_lookup puts the table for a host shader:
/// storage points of its own beside a technique module's (GlBindings) and
/// a light buffer's (GlLightBindings), and a uniform point for the block
/// HabufferSpatial (the table's size, age bits, domain and fold).
struct GlSpatialBindings {
  unsigned table = GlBindings::kDefaultStorageBase + 12;    ///< the slots (64-bit records)
  unsigned max_age = GlBindings::kDefaultStorageBase + 13;  ///< the max-age cells
  unsigned offsets = GlBindings::kDefaultStorageBase + 14;  ///< the offsets of the probe sequence
  unsigned params = GlBindings::kDefaultUniformBase + 2;    ///< the block HabufferSpatial
  /// Throws GlError when a point coincides with one of `view`'s or another
  /// of these, or is beyond this context's limits; needs a current context.
  void validate(const GlBindings& view) const;
  /// "#define HABUFFER_SPATIAL_BINDING_TABLE 28\n..." (TABLE, MAX_AGE,
  /// OFFSETS, PARAMS), for spatial_lookup_part; with `overridable`, each
  /// inside #ifndef (the installed file).
  [[nodiscard]] std::string glsl_defines(bool overridable = false) const;
};

/// The GLSL a host shader appends (after its `#version 450` line, at global
/// scope, beside a technique module or without one) to look the table up:
/// the points of `bindings`, the block HabufferSpatial, the read-only
/// table, max-age cells and offsets, the shared probe, record and key
/// sources under the prefix sh_, and habuffer_spatial_find /
/// habuffer_spatial_find_value (see the file comment). Slots are read as
/// uvec2, so it needs no 64-bit integers (any atomic mode). Reserved names:
/// sh_*, habuffer_spatial*, HabufferSpatial*, HABUFFER_SPATIAL_*,
/// HABUFFER_SH_*. With `overridable`, the points sit inside #ifndef.
std::string spatial_lookup_part(const GlSpatialBindings& bindings = {}, bool overridable = false);

/// One table on the GPU of the current context. Its buffers go to the
/// points of `GlBindings` (table, max_age, offsets, locks, the parameter
/// block at `params`; the passes' stream, deferred, capture and counters),
/// and a GlStateGuard puts the host's bindings and program back before each
/// call returns.
///
/// Every call checks its arguments before any GL work, so a refused call
/// changes nothing: the rule (insert), the spans' sizes, and every key in
/// the domain (keys outside it would alias real keys: (5, 134, 7) would read
/// as (5, 6, 15) in a 16 x 128 x 16 domain).
class GlSpatialHash {
 public:
  /// Uploads `table`: its parameters, offsets, slots and max-age cells. Any
  /// table may be uploaded, whatever its rule: lookups do not depend on the
  /// rule (its encoding is in the stored values); insert() refuses First and
  /// Last. Throws GlError when the context lacks 64-bit integers in shaders,
  /// or a buffer beyond the driver's shader-storage limit.
  explicit GlSpatialHash(const spatial::SpatialHash& table, const GlBindings& bindings = {});

  /// A key that failed (its record carried past AMAX ages or the iteration
  /// limit): the caller grows the table and inserts it again.
  struct Dropped {
    glm::uvec3 key;
    std::uint32_t stored;  ///< the value as stored (the rule's encoding)
  };
  /// Inserts each key with its stored value (the rule's encoding: Max
  /// stores the value, Min its complement; `stored` empty: every value 0, a
  /// set). Calls cut short (a busy emulated lock, the driver's loop budget)
  /// are resumed by further passes until none is left. Returns the
  /// counters; failed calls' records go to `dropped`. Throws
  /// std::invalid_argument, nothing inserted, for rule First or Last (they
  /// order a batch, which concurrent GPU calls do not: use max or min, or
  /// the CPU table), `stored` neither empty nor keys.size(), more than
  /// 2^32 - 1 keys, or a key outside the domain (naming the first).
  spatial::InsertReport insert(std::span<const glm::uvec3> keys, std::span<const std::uint32_t> stored,
                               std::vector<Dropped>& dropped);
  /// The same from the host's own GL buffers, without the keys passing
  /// through the CPU: `count` keys from byte 0 of buffer `keys`, 16 bytes a
  /// key, (x, y, z, ignored) as std430 `uvec3[]` or `uvec4[]` lay them out;
  /// their stored values as `uint[]` from byte 0 of buffer `stored` (0: every
  /// value 0). A barrier for the host's shader writes to them comes first.
  /// The keys are folded and checked on the GPU before any insert pass:
  /// when some are outside the domain, throws std::invalid_argument naming
  /// how many, the first one's index and key, and the domain, and the table
  /// is unchanged (nothing inserted, nothing aliased). Throws
  /// std::invalid_argument first, nothing done, for rule First or Last, a
  /// name that is not a buffer, or a buffer smaller than `count` keys or
  /// values need.
  spatial::InsertReport insert(unsigned keys, unsigned stored, std::uint32_t count, std::vector<Dropped>& dropped);
  /// Batched lookup: found[i] and the stored value (0 where absent) of keys[i].
  /// Returns the keys found. Throws std::invalid_argument, before any GL
  /// work, when `stored` or `found` is not exactly keys.size() long (a
  /// longer span would hide a caller's mix-up as a shorter one corrupts
  /// memory), for more than 2^32 - 1 keys, or for a key outside the domain
  /// (naming the first): as SpatialHash::find.
  std::uint64_t find(std::span<const glm::uvec3> keys, std::span<std::uint32_t> stored,
                     std::span<std::uint8_t> found) const;

  /// Binds the table, its max-age cells and offsets (shader-storage) and its
  /// parameter block (uniform) at `bindings`' points, for a host's draw or
  /// dispatch whose shaders hold spatial_lookup_part(bindings). Indexed
  /// bindings only: the host's generic bindings stay. The host issues
  /// glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT) after an insert, before
  /// the draw that reads. Throws GlError for points that coincide with the
  /// GlBindings this table was made with or exceed the context's limits.
  void bind_for_lookup(const GlSpatialBindings& bindings = {}) const;

  /// Empties the table on the GPU (its size kept).
  void clear();
  /// GPU time of the last insert's or find's passes (GPU timestamps around
  /// the dispatches: no transfers), in milliseconds; 0 on Mesa's software
  /// rasterizers, whose timestamps time the submission only.
  [[nodiscard]] double gpu_ms() const { return gpu_ms_; }

  /// The slots and max-age cells read back.
  [[nodiscard]] std::vector<std::uint64_t> slots() const;
  [[nodiscard]] std::vector<std::uint32_t> max_age() const;
  /// The miss filter's words (SpatialHash::filter()'s layout; empty without one).
  [[nodiscard]] std::vector<std::uint32_t> filter() const;
  /// native64 or emulated64.
  [[nodiscard]] AtomicMode mode() const { return mode_; }
  /// Resume passes the last insert needed (0: none was cut short).
  [[nodiscard]] std::uint32_t resume_passes() const { return resume_passes_; }

 private:
  // The constructor's work on the context's info, queried once.
  GlSpatialHash(const spatial::SpatialHash& table, const GlBindings& bindings, const GlInfo& info);
  void bind_table() const;  // the table's buffers and block at GlBindings' points
  ContextBound context_;    // first: every call checks its context (gl_context.h)
  // Records from keys and values in GL buffers (refused when a key is
  // outside the domain, the table unchanged), then the insert passes.
  spatial::InsertReport insert_buffers(unsigned keys, unsigned stored, std::uint32_t count,
                                       std::vector<Dropped>& dropped);
  GlStorage make_records(unsigned keys, unsigned stored, std::uint32_t count) const;
  spatial::InsertReport insert_records(const GlStorage& records, std::uint32_t count, std::vector<Dropped>& dropped);
  GlBindings bindings_;
  spatial::SpatialHashConfig config_;
  spatial::FoldedDomain fold_;
  AtomicMode mode_;
  bool timed_;  // GL_TIME_ELAPSED times the shaders (not on Mesa's software rasterizers)
  ShaderProgram records_, insert_, find_;
  std::uint64_t slot_count_ = 0, cell_count_ = 0, filter_count_ = 0;
  GlStorage table_, max_age_, offsets_, locks_, params_;
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
