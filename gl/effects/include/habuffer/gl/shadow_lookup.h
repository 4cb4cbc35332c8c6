/// @file
/// Translucent shadows on the GPU (seed 000, section 6): a light buffer (an
/// HA-buffer the host gathered from the light's view, GlHaTable) looked up
/// from the shaders of another frame, the view's, whatever its technique.
/// The view shader appends light_lookup_part() to its module and calls
///
///   float habuffer_shadow_transmittance(vec3 world_point);
///   float habuffer_shadow_transmittance(uvec2 light_pixel, float light_depth);
///
/// which walk the light buffer's records with the very shared sources the
/// CPU path runs (shared/ha_traverse.glsl's ha_transmittance, instantiated
/// under the prefix hs_ beside the view's own ha_ instance), so a receiver
/// mapped to the same light pixel and depth gets the same transmittance bit
/// for bit (habuffer/transmittance.h has the formula and the bias rule).
#pragma once

#include <cstdint>
#include <string>

#include <glm/mat4x4.hpp>

#include "habuffer/extent.h"
#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/light_mapping.h"

namespace habuffer::gl {

class GlHaTable;

/// Where the light buffer is bound for the lookup: storage points of its own
/// beside the view's (GlBindings), and a uniform point for its block.
struct GlLightBindings {
  unsigned table = GlBindings::kDefaultStorageBase + 9;     ///< the light buffer's records
  unsigned max_age = GlBindings::kDefaultStorageBase + 10;  ///< its max-age table
  unsigned offsets = GlBindings::kDefaultStorageBase + 11;  ///< its offsets
  unsigned params = GlBindings::kDefaultUniformBase + 1;    ///< the block HabufferLight
  /// Throws GlError when a point coincides with one of `view`'s or another
  /// of these, or is beyond this context's limits; needs a current context.
  void validate(const GlBindings& view) const;
  /// "#define HABUFFER_LIGHT_BINDING_TABLE 25\n...", for light_lookup_part;
  /// with `overridable`, each inside #ifndef (the installed file).
  [[nodiscard]] std::string glsl_defines(bool overridable = false) const;
};

/// The GLSL a view module appends for the lookup (see the file comment): the
/// light buffer's environment at `bindings`, the shared record, probe, blend
/// and traversal sources under the prefix hs_, and the two
/// habuffer_shadow_transmittance functions. Throws GlError for atomic mode
/// native32: the lookup reads 64-bit records, which need 64-bit shader
/// integers (the view module's mode native64 or emulated64).
/// With `overridable`, the points sit inside #ifndef (the installed file).
std::string light_lookup_part(const GlLightBindings& bindings, AtomicMode mode, bool overridable = false);

/// The same for a shader without a technique module (a host's opaque
/// pass): `#version 450 core`, the mode's extensions, the constants and
/// GLSL environment the shared sources need, then light_lookup_part. The
/// shader's own code follows. Throws GlError for native32.
std::string light_lookup_shader_head(const GlLightBindings& bindings, AtomicMode mode);

/// A light buffer ready for lookups: its parameter block (mapping, table,
/// bias) and the binding of its buffers (see the file comment).
class GlShadowLookup {
 public:
  /// `light` must hold L64 records (colour and opacity) and stay alive while
  /// this is used. Throws std::invalid_argument for L32 records and GlError
  /// for bindings that collide with `view` or exceed this context's limits,
  /// or for a light buffer already gathered with depths `mapping` does not
  /// compare (check_depths).
  GlShadowLookup(const GlHaTable& light, const GlLightMapping& mapping, std::uint32_t bias,
                 const GlBindings& view = {}, const GlLightBindings& bindings = {});
  /// Writes the block again from the light buffer's current table and from
  /// `mapping` (a light that moved).
  void update(const GlLightMapping& mapping);
  /// Binds the light buffer and the block at their points (indexed
  /// bindings only; the host's generic bindings stay), for the view's gather.
  /// A light buffer whose table or screen changed since the block was
  /// written (adaptive sizing, lossless growth, a resize) gets the block
  /// written again first, so a lookup never probes a table it does not hold.
  /// Throws GlError as check_depths.
  void bind();
  /// Throws a one-line GlError when the light buffer's last frame stored
  /// depths that this lookup's mapping does not compare
  /// (light_depth_mismatch): gathered for another GlFrameOptions::light, or
  /// window depth (no light given to its driver) under a light whose t it
  /// is not, a perspective one above all. Nothing before the first frame.
  void check_depths() const;
  /// The bindings the shaders were assembled with.
  [[nodiscard]] const GlLightBindings& bindings() const { return bindings_; }
  /// Bytes of the block (the light buffer's own are its container's).
  [[nodiscard]] std::uint64_t memory_bytes() const { return params_.bytes(); }

 private:
  const GlHaTable& light_;
  GlLightBindings bindings_;
  std::uint32_t bias_;
  GlLightMapping mapping_;
  Extent written_table_, written_screen_;  ///< the light buffer's sizes the block holds
  GlStorage params_;
};

}  // namespace habuffer::gl
