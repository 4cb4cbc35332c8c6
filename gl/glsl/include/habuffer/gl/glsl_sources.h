/// @file
/// The shared algorithm as GLSL text (embedded from core/{record,hash}/include/habuffer/shared/ and
/// gl/glsl/shaders/ at build time) and the assembly of complete shaders from it.
#pragma once

#include <string>
#include <utility>
#include <string_view>
#include <vector>

#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/technique.h"

namespace habuffer::gl {

extern const char* const kHaConstants;          ///< shared/ha_constants.h: constants shared verbatim with the C++ path
extern const char* const kHaRecord;             ///< shared/ha_record.glsl: record packing (SPEC 2)
extern const char* const kHaCarry;              ///< shared/ha_carry.glsl: an insert call's state between steps
extern const char* const kHaSaturation;         ///< shared/ha_saturation.glsl: saturation depth
extern const char* const kSaturationEnv;        ///< gl/glsl/shaders/saturation_env.glsl: saturation depth's environment
extern const char* const kHaProbe;              ///< shared/ha_probe.glsl: coherent probing (SPEC 3-5)
extern const char* const kHaInsert;             ///< shared/ha_insert.glsl: insertion (SPEC 6)
extern const char* const kHaBlend;              ///< shared/ha_blend.glsl: front-to-back compositing (SPEC 7)
extern const char* const kHaShadow;            ///< shared/ha_shadow.glsl: translucent shadows' per-record step
extern const char* const kHaShadowPcf;         ///< shared/ha_shadow_pcf.glsl: translucent shadows' 2x2 filtering
extern const char* const kHaLightMap;          ///< shared/ha_light_map.glsl: a world point in a light's view
extern const char* const kHaTraverse;           ///< shared/ha_traverse.glsl: traversal (SPEC 7)
extern const char* const kHaEntries;            ///< shared/ha_entries.glsl: a pixel's entries, sorted after the gather
extern const char* const kPointStreamVertex;    ///< gl/glsl/shaders/point_stream.vert.glsl: a stream drawn as points
extern const char* const kPointStreamFragment;  ///< gl/glsl/shaders/point_stream.frag.glsl: their insert
extern const char* const kGlslEnv;              ///< gl/glsl/shaders/glsl_env.glsl: GLSL spellings for the shared sources
extern const char* const kEntryCommon;          ///< gl/glsl/shaders/entry_common.glsl: outcome tallies and capture
extern const char* const kSortedEnv;            ///< gl/glsl/shaders/sorted_env.glsl: the private array of the sort
extern const char* const kInsertEntry;          ///< gl/glsl/shaders/insert_entry.glsl: every technique's insertion entry
extern const char* const kSortCompute;          ///< gl/glsl/shaders/sort.comp.glsl: the sort pass
extern const char* const kPreludeNative;        ///< gl/glsl/shaders/prelude_native.glsl: atomic modes native32 and native64
extern const char* const kPreludeEmulated64;    ///< gl/glsl/shaders/prelude_emulated64.glsl: atomic mode emulated64
extern const char* const kInsertStreamCompute;  ///< gl/glsl/shaders/insert_stream.comp.glsl: the compute entry
extern const char* const kResumeCompute;        ///< gl/glsl/shaders/resume.comp.glsl: the resume pass
extern const char* const kFullScreenVertex;     ///< gl/glsl/shaders/clear_pass.vert.glsl: one triangle covering the viewport
extern const char* const kLightEnv;             ///< gl/glsl/shaders/light_env.glsl: a light buffer's environment (translucent shadows)
extern const char* const kLightLookup;          ///< gl/glsl/shaders/light_lookup.glsl: habuffer_shadow_transmittance
extern const char* const kResolveFragment;      ///< gl/glsl/shaders/resolve.frag.glsl: the resolve pass

/// The stage a module is for (Fragment defines HABUFFER_STAGE_FRAGMENT).
enum class ShaderStage { Compute, Fragment };

/// The HA-buffer module a shader appends its own code to: the #version line,
/// the extensions the atomic mode needs, `header` (the host's own #extension
/// lines and defines, which must precede any code), then
/// technique_module_body(). Do not repeat #version.
std::string ha_module(AtomicMode mode, const GlBindings& bindings, ShaderStage stage, std::string_view header = {});
/// The same for any technique: its buffers and algorithm, and the same entry
/// habuffer_insert(pixel, depth, rgba) (outcomes HABUFFER_*, counted). The atomic
/// mode fixes the record layout (native32: L32, else L64) for every technique.
std::string technique_module(Technique technique, AtomicMode mode, const GlBindings& bindings, ShaderStage stage,
                             std::string_view header = {});

/// The #extension lines `mode` needs ("" for native32). They must come before
/// any code of the shader, so a host that places the module after its own
/// declarations puts these right after its #version line.
std::string module_extensions(AtomicMode mode);
/// The module without #version and #extension lines, to follow a host's own
/// declarations anywhere at global scope: the binding points
/// (HABUFFER_BINDING_*; with `overridable_bindings`, each inside #ifndef so a
/// host may #define it first), the shared constants (HABUFFER_*), the
/// parameter block `HabufferParams habuffer_params`, the technique's buffers
/// and algorithm, and the entries habuffer_insert(uvec2 pixel, float depth, uint
/// rgba) and habuffer_insert(uvec2 pixel, float depth). Every name it declares
/// starts with ha_, Ha, habuffer_, HABUFFER_ or a technique's prefix (ll_,
/// fa_, sl_, kb_).
std::string technique_module_body(Technique technique, AtomicMode mode, const GlBindings& bindings, ShaderStage stage,
                                  bool overridable_bindings = false);


/// The compute shader that inserts a fragment stream held in a buffer.
std::string insert_stream_compute(AtomicMode mode, const GlBindings& bindings = {});
/// The same for any technique (the overload above is the HA-buffer's).
std::string insert_stream_compute(Technique technique, AtomicMode mode, const GlBindings& bindings = {});
/// The compute entry's form for the blended baselines (wboit, blend), whose
/// insert needs the fixed-function blender: vertex and fragment shaders that
/// draw the stream as points, one per fragment in stream order.
std::pair<std::string, std::string> insert_stream_points(Technique technique, AtomicMode mode,
                                                         const GlBindings& bindings = {});

/// A complete shader as the library compiles it, for checks by a reference
/// compiler: `name` is unique per mode ("insert", "clear", ...), `stage` the
/// file extension glslangValidator reads the stage from ("comp", "frag", "vert").
struct ShaderSource {
  /// The name, the stage's file extension and the complete source.
  std::string name, stage, source;
};
/// Every shader the library compiles for `mode` (the HA-buffer's compute
/// entry, resume, clear and resolve passes; every other technique's compute
/// entry, sort and resolve passes, named "lists-insert", ...). Needs no GL context.
std::vector<ShaderSource> library_shaders(AtomicMode mode, const GlBindings& bindings = {});

/// The full-screen passes' shaders: one vertex shader, and the clear pass's
/// and resolve pass's fragment shaders (the module plus their own code).
std::string full_screen_vertex();
/// The HA-buffer's resolve pass fragment shader.
std::string resolve_fragment(AtomicMode mode, const GlBindings& bindings);
/// The same for any technique.
std::string resolve_fragment(Technique technique, AtomicMode mode, const GlBindings& bindings);

/// How a resolve pass composites a multisampled buffer (BufferConfig::samples
/// above 1; docs/spec-notes.md, "Multisampled records").
enum class SampleResolve {
  /// Per pixel: each sample composites the records its mask names, the
  /// pixel is their mean (into a single-sampled target; the CPU path's
  /// FragmentBuffer::composite_image, bit for bit).
  Pixel,
  /// Per sample: drawn into a multisampled target of the same samples, each
  /// sample's invocation (gl_SampleID) composites its own records; the
  /// host's MSAA resolve (a blit) averages them afterwards.
  Sample,
};
/// The resolve pass of a buffer of `samples` per pixel (1: the one above) resolved as `how`.
std::string resolve_fragment(Technique technique, AtomicMode mode, const GlBindings& bindings, std::uint32_t samples,
                             SampleResolve how);

/// The sort pass of the techniques that sort after the gather (one
/// invocation per pixel); throws GlError for the HA-buffer.
std::string sort_compute(Technique technique, AtomicMode mode, const GlBindings& bindings = {});

/// The resume pass: runs deferred insert calls (cut short by a lock or the
/// driver's loop budget) on from their carried state.
std::string resume_compute(AtomicMode mode, const GlBindings& bindings = {});
/// The same for any technique (the overload above is the HA-buffer's).
std::string resume_compute(Technique technique, AtomicMode mode, const GlBindings& bindings = {});

}  // namespace habuffer::gl
