/// @file
/// Where the GPU path's buffers are bound. Host apps choose the points so our
/// buffers do not collide with theirs; the GLSL module is assembled with the
/// same numbers (#define HABUFFER_BINDING_*), so a host shader and bind()
/// always agree.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace habuffer::gl {

/// Binding points of the GPU path's buffers, each named by what it holds.
/// A GLSL module holds one technique, so the techniques' own buffers take
/// the same first points by default (the HA-buffer's table, the lists'
/// heads, the arrays' counts, the k-buffer's slots and the blended
/// accumulator all at kDefaultStorageBase): each is still its own member and
/// its own HABUFFER_BINDING_ name, moved on its own, never another
/// technique's point under an alias. The points every technique shares
/// (counters, locks, capture, stream, deferred, saturation) follow. The
/// defaults start at 16 (kDefaultStorageBase, kDefaultUniformBase), above
/// the points hosts use first; from_base() moves them as a block. Every
/// point is checked against the context's limits when a container is made
/// (validate()), before it compiles a shader with them.
struct GlBindings {
  static constexpr unsigned kDefaultStorageBase = 16;  ///< the first shader-storage point by default
  static constexpr unsigned kDefaultUniformBase = 16;  ///< the uniform-buffer point by default
  /// Points of one technique's own buffers (the most any technique has):
  /// the shared points start this far past the base.
  static constexpr unsigned kTechniquePoints = 3;

  /// The HA-buffer's buffers.
  unsigned table = kDefaultStorageBase;        ///< the hash table's records
  unsigned max_age = kDefaultStorageBase + 1;  ///< the max-age table
  unsigned offsets = kDefaultStorageBase + 2;  ///< the offsets of the probe sequence
  /// The node lists' buffers (lists, sorted-lists, paged-lists).
  unsigned heads = kDefaultStorageBase;      ///< each pixel's first node
  unsigned nodes = kDefaultStorageBase + 1;  ///< the node pool's entries
  unsigned links = kDefaultStorageBase + 2;  ///< the node pool's links
  /// Fixed arrays' buffers.
  unsigned counts = kDefaultStorageBase;      ///< fragments each pixel received
  unsigned layers = kDefaultStorageBase + 1;  ///< K entries per pixel
  /// The k-buffer's buffers.
  unsigned slots = kDefaultStorageBase;          ///< K records per pixel
  unsigned occupancy = kDefaultStorageBase + 1;  ///< the occupancy map (with occupancy culling)
  unsigned limits = kDefaultStorageBase + 2;     ///< each pixel's depth limit (with occupancy culling)
  /// The blended baselines' buffers (wboit, blend).
  unsigned accum = kDefaultStorageBase;          ///< the accumulator's copy the resolve reads
  unsigned revealage = kDefaultStorageBase + 1;  ///< wboit's revealage copy the resolve reads
  /// Buffers every technique (or the frame driver) may use.
  unsigned counters = kDefaultStorageBase + 3;    ///< the outcome tallies
  unsigned locks = kDefaultStorageBase + 4;       ///< emulated64's lock words (HA-buffer, k-buffer)
  unsigned capture = kDefaultStorageBase + 5;     ///< captured fragments (GlFrameOptions::capture)
  unsigned stream = kDefaultStorageBase + 6;      ///< the compute entry's fragments, the resume pass's calls
  unsigned deferred = kDefaultStorageBase + 7;    ///< insert calls cut short, for the resume pass
  unsigned saturation = kDefaultStorageBase + 8;  ///< the saturation depth image (HA-buffer, sorted-lists)
  /// Uniform-buffer binding point of the parameter block (HabufferParams).
  unsigned params = kDefaultUniformBase;

  /// Every technique's own buffers from `storage_base` (each technique's
  /// first buffer there, its next ones after it), the shared ones from
  /// `storage_base` + kTechniquePoints in the order of the members (so
  /// `saturation` is `storage_base` + 8), and the parameter block at `uniform_base`.
  [[nodiscard]] static GlBindings from_base(unsigned storage_base, unsigned uniform_base);

  /// One shader-storage point: its member's name (also its GLSL name,
  /// upper-cased after HABUFFER_BINDING_), the member, and the group of
  /// buffers one module may bind together with it.
  struct Point {
    const char* name;          ///< "heads"
    unsigned GlBindings::*member;  ///< &GlBindings::heads
    /// The technique group it belongs to: 0 shared by all; otherwise points
    /// of one group must differ from each other and from the shared ones.
    unsigned group;
  };
  /// Every shader-storage point, shared ones first.
  [[nodiscard]] static std::span<const Point> points();
  /// Every distinct shader-storage point in use, ascending (what a state
  /// guard saves and restores).
  [[nodiscard]] std::vector<unsigned> storage_points() const;
  /// Throws GlError when two points one module binds together coincide (a
  /// technique's own buffers among themselves or with a shared one, or two
  /// shared ones) or a point is at or beyond the context's limits
  /// (GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, GL_MAX_UNIFORM_BUFFER_BINDINGS);
  /// needs a current context.
  void validate() const;
  /// "#define HABUFFER_BINDING_TABLE 16\n..." for the module assembly: every
  /// point's name (HABUFFER_BINDING_TABLE, _MAX_AGE, _OFFSETS, _HEADS,
  /// _NODES, _LINKS, _COUNTS, _LAYERS, _SLOTS, _OCCUPANCY, _LIMITS, _ACCUM,
  /// _REVEALAGE, _COUNTERS, _LOCKS, _CAPTURE, _STREAM, _DEFERRED,
  /// _SATURATION) and _PARAMS (uniform); with `overridable`, each inside
  /// #ifndef (the installed GLSL files). What a host defines before an
  /// installed file, for the points it moved.
  [[nodiscard]] std::string glsl_defines(bool overridable = false) const;
  /// "HABUFFER_BINDING_HEADS" for the point named "heads": the macro a
  /// module's GLSL reads a point's number from.
  [[nodiscard]] static std::string macro_name(const char* point);
};

}  // namespace habuffer::gl
