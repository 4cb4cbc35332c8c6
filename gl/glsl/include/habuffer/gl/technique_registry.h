/// @file
/// The GPU path's half of a technique's descriptor: its GLSL module parts and
/// its GL container's factory, declared once in the technique's gl folder
/// (techniques/NAME/gl/) and listed here in
/// technique_list.h's order. The CPU half (properties, memory model, CPU
/// container) is habuffer/technique_descriptor.h.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/technique.h"

namespace habuffer {
struct OffsetSource;
}  // namespace habuffer

namespace habuffer::gl {

class GlTechnique;  // gl_technique.h: the frames layer above this one

/// One technique on the GPU (see above).
struct GlTechniqueDescriptor {
  Technique technique;  ///< its enumerator (technique_list.h)
  /// The module's technique part after the shared prelude: the names the
  /// passes call, as macros (HABUFFER_TECHNIQUE_CALL, _SORT, _COMPOSITE, ...),
  /// then its environment and the shared sources it needs, in order.
  std::string (*module_parts)(AtomicMode mode);
  /// Its GL container (the caller has a current context).
  std::unique_ptr<GlTechnique> (*make)(const TechniqueConfig& config, const OffsetSource& offsets, AtomicMode mode,
                                       const GlBindings& bindings, std::uint32_t clear_tile);
  /// The library shaders of its own beyond the insert, sort and resolve
  /// passes every technique has (library_shaders()); nullptr for none.
  std::vector<ShaderSource> (*own_shaders)(AtomicMode mode, const GlBindings& bindings);
  /// Its own buffers' group in GlBindings::points() (the HA-buffer's 1, the
  /// node lists' 2, ...): the binding names its module declares besides the
  /// shared ones.
  unsigned binding_group;
};

/// The GPU descriptor of `t` (every enumerator has one).
const GlTechniqueDescriptor& gl_descriptor(Technique t);

/// "a\nb\n": each part followed by a newline, as the module joins them.
std::string join_parts(std::initializer_list<const char*> parts);
/// The emulated64 or native prelude of `mode` (the 64-bit atomics' emulation).
const char* mode_prelude(AtomicMode mode);

}  // namespace habuffer::gl
