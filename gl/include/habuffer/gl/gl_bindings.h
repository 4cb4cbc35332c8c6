/// @file
/// Where the GPU path's buffers are bound. Host apps choose the points so our
/// buffers do not collide with theirs; the GLSL module is assembled with the
/// same numbers (#define HABUFFER_BINDING_*), so a host shader and bind()
/// always agree.
#pragma once

#include <array>
#include <span>
#include <string>

namespace habuffer::gl {

/// Binding points of the GPU path's buffers. The defaults start at 16
/// (kDefaultStorageBase, kDefaultUniformBase), above the points hosts use
/// first; from_base() moves them as a block. Every point is checked against
/// the context's limits when a container is made (validate()), before it
/// compiles a shader with them.
struct GlBindings {
  static constexpr unsigned kDefaultStorageBase = 16;  ///< the first shader-storage point by default
  static constexpr unsigned kDefaultUniformBase = 16;  ///< the uniform-buffer point by default
  /// Shader-storage binding points.
  unsigned table = kDefaultStorageBase;           ///< the HA table, list heads, array counts
  unsigned max_age = kDefaultStorageBase + 1;     ///< the max-age table, list nodes, array layers
  unsigned offsets = kDefaultStorageBase + 2;     ///< the HA offsets, list links
  unsigned counters = kDefaultStorageBase + 3;    ///< the outcome tallies
  unsigned locks = kDefaultStorageBase + 4;       ///< emulated64's lock words
  unsigned capture = kDefaultStorageBase + 5;     ///< captured fragments (GlFrameOptions::capture)
  unsigned stream = kDefaultStorageBase + 6;      ///< the compute entry's fragments, the resume pass's calls
  unsigned deferred = kDefaultStorageBase + 7;    ///< insert calls cut short, for the resume pass
  unsigned saturation = kDefaultStorageBase + 8;  ///< the saturation depth image
  /// Uniform-buffer binding point of the parameter block (HabufferParams).
  unsigned params = kDefaultUniformBase;

  /// Nine consecutive storage points from `storage_base` (in the order of
  /// the members) and the parameter block at `uniform_base`.
  [[nodiscard]] static GlBindings from_base(unsigned storage_base, unsigned uniform_base);

  /// The nine shader-storage points, in the order of the members.
  [[nodiscard]] std::array<unsigned, 9> storage_points() const {
    return {table, max_age, offsets, counters, locks, capture, stream, deferred, saturation};
  }
  /// Throws GlError when two storage points coincide or a point is at or beyond
  /// the context's limits (GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS,
  /// GL_MAX_UNIFORM_BUFFER_BINDINGS); needs a current context.
  void validate() const;
  /// "#define HABUFFER_BINDING_TABLE 16\n..." for the module assembly: the
  /// ten documented names, HABUFFER_BINDING_TABLE, _MAX_AGE, _OFFSETS,
  /// _COUNTERS, _LOCKS, _CAPTURE, _STREAM, _DEFERRED, _SATURATION (storage)
  /// and _PARAMS (uniform); with `overridable`, each inside #ifndef (the
  /// installed GLSL files). What a host defines before an installed file.
  [[nodiscard]] std::string glsl_defines(bool overridable = false) const;
  /// A binding name of another technique's buffer and the documented name
  /// whose point it takes (HEADS is TABLE's point, ...).
  struct DerivedName {
    const char* name;  ///< after HABUFFER_BINDING_
    const char* of;    ///< the documented name it is defined as
  };
  /// Every derived name: the module defines each as its documented name (a
  /// host never defines them; one that does gets an #error).
  [[nodiscard]] static std::span<const DerivedName> derived_names();
};

}  // namespace habuffer::gl
