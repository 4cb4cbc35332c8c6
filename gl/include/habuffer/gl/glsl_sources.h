/// @file
/// The shared algorithm as GLSL text (embedded from core/include/habuffer/shared/ and
/// gl/shaders/ at build time) and the assembly of complete shaders from it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/technique.h"

namespace habuffer::gl {

extern const char* const kHaConstants;
extern const char* const kHaRecord;
extern const char* const kHaCarry;
extern const char* const kHaSaturation;
extern const char* const kHaSortedLists;
extern const char* const kHaKBuffer;
extern const char* const kSaturationEnv;
extern const char* const kSortedListsEnv;
extern const char* const kKBufferEnv;
extern const char* const kKBufferEntry;
extern const char* const kKBufferCountCompute;
extern const char* const kHaProbe;
extern const char* const kHaInsert;
extern const char* const kHaBlend;
extern const char* const kHaTraverse;
extern const char* const kHaEntries;
extern const char* const kHaLists;
extern const char* const kHaArrays;
extern const char* const kGlslEnv;
extern const char* const kEntryCommon;
extern const char* const kHaEnv;
extern const char* const kListsEnv;
extern const char* const kArraysEnv;
extern const char* const kSortedEnv;
extern const char* const kInsertEntry;
extern const char* const kSortCompute;
extern const char* const kPreludeNative;
extern const char* const kPreludeEmulated64;
extern const char* const kHaEntry;
extern const char* const kInsertStreamCompute;
extern const char* const kResumeCompute;
extern const char* const kFullScreenVertex;
extern const char* const kClearPassFragment;
extern const char* const kResolveFragment;

enum class ShaderStage { Compute, Fragment };

/// The HA-buffer module a shader appends its own code to: the #version line,
/// the extensions the atomic mode needs, `header` (the host's own #extension
/// lines and defines, which must precede any code), then
/// technique_module_body(). Do not repeat #version.
std::string ha_module(AtomicMode mode, const GlBindings& bindings, ShaderStage stage, std::string_view header = {});
/// The same for any technique: its buffers and algorithm, and the same entry
/// ha_insert(pixel, depth, rgba) (outcomes HABUFFER_*, counted). The atomic
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
/// and algorithm, and the entries ha_insert(uvec2 pixel, float depth, uint
/// rgba) and ha_insert(uvec2 pixel, float depth). Every name it declares
/// starts with ha_, Ha, habuffer_, HABUFFER_ or a technique's prefix (ll_,
/// fa_, sl_, kb_).
std::string technique_module_body(Technique technique, AtomicMode mode, const GlBindings& bindings, ShaderStage stage,
                                  bool overridable_bindings = false);

/// A file of the GLSL a host's file-based shader pipeline includes, as
/// installed under share/habuffer/glsl: `path` relative to that directory.
struct GlslFile {
  std::string path, text;
};
/// Every such file: for each atomic mode, <mode>/extensions.glsl, and for each
/// technique with a GL path <mode>/<technique>.frag.glsl and .comp.glsl
/// (technique_module_body at the default, overridable bindings), with a
/// comment header saying how to use them. Needs no GL context.
std::vector<GlslFile> host_glsl_files();

/// The compute shader that inserts a fragment stream held in a buffer.
std::string insert_stream_compute(AtomicMode mode, const GlBindings& bindings = {});
std::string insert_stream_compute(Technique technique, AtomicMode mode, const GlBindings& bindings = {});

/// A complete shader as the library compiles it, for checks by a reference
/// compiler: `name` is unique per mode ("insert", "clear", ...), `stage` the
/// file extension glslangValidator reads the stage from ("comp", "frag", "vert").
struct ShaderSource {
  std::string name, stage, source;
};
/// Every shader the library compiles for `mode` (the HA-buffer's compute
/// entry, resume, clear and resolve passes; every other technique's compute
/// entry, sort and resolve passes, named "lists-insert", ...). Needs no GL context.
std::vector<ShaderSource> library_shaders(AtomicMode mode, const GlBindings& bindings = {});

/// The full-screen passes' shaders: one vertex shader, and the clear pass's
/// and resolve pass's fragment shaders (the module plus their own code).
std::string full_screen_vertex();
std::string clear_pass_fragment(AtomicMode mode, const GlBindings& bindings);
std::string resolve_fragment(AtomicMode mode, const GlBindings& bindings);
std::string resolve_fragment(Technique technique, AtomicMode mode, const GlBindings& bindings);

/// The sort pass of the techniques that sort after the gather (one
/// invocation per pixel); throws GlError for the HA-buffer.
std::string sort_compute(Technique technique, AtomicMode mode, const GlBindings& bindings = {});

/// The resume pass: runs deferred insert calls (cut short by a lock or the
/// driver's loop budget) on from their carried state.
std::string resume_compute(AtomicMode mode, const GlBindings& bindings = {});
std::string resume_compute(Technique technique, AtomicMode mode, const GlBindings& bindings = {});
/// The k-buffer's occupancy count pass.
std::string kbuffer_count_compute(AtomicMode mode, const GlBindings& bindings = {});

}  // namespace habuffer::gl
