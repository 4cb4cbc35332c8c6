#include <algorithm>
#include <cctype>
#include <span>
#include <string>

#include <epoxy/gl.h>

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_spatial_hash.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/module_variant.h"
#include "habuffer/gl/shadow_lookup.h"
#include "habuffer/gl/technique_registry.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::gl {
namespace {

const char* mode_extensions(AtomicMode mode) {
  switch (mode) {
    case AtomicMode::Native32: return "";
    case AtomicMode::Native64:
      return "#extension GL_ARB_gpu_shader_int64 : require\n#extension GL_NV_shader_atomic_int64 : require\n";
    case AtomicMode::Emulated64: return "#extension GL_ARB_gpu_shader_int64 : require\n";
  }
  return "";
}

// The record word of the mode's layout (SPEC 2), as hash_kernel.h's Word,
// and its split into (low, high) 32-bit words for deferred calls.
const char* word_defines(AtomicMode mode) {
  if (mode == AtomicMode::Native32)
    return "#define ha_word uint\nconst uint ha_word_bits = 32u;\nconst uint ha_payload_bits = 0u;\n"
           "#define ha_word_split(r) uvec2(r, 0u)\n#define ha_word_join(v) (v).x\n";
  return "#define ha_word uint64_t\nconst uint ha_word_bits = 64u;\nconst uint ha_payload_bits = 32u;\n"
         "#define ha_word_split(r) unpackUint2x32(r)\n#define ha_word_join(v) packUint2x32(v)\n";
}


// The parameter block of ha_params.h, read here as a list of (GLSL type, name).
struct ParamField {
  const char* type;
  const char* name;
};
#define HABUFFER_PARAMS_BEGIN constexpr ParamField kParamFields[] = {
#define HABUFFER_PARAMS_END };
#define HABUFFER_PARAM_UINT(name) {"uint", #name},
#define HABUFFER_PARAM_FLOAT(name) {"float", #name},
#define HABUFFER_PARAM_UVEC2(name) {"uvec2", #name},
#include "habuffer/shared/ha_params.h"
#undef HABUFFER_PARAMS_BEGIN
#undef HABUFFER_PARAMS_END
#undef HABUFFER_PARAM_UINT
#undef HABUFFER_PARAM_FLOAT
#undef HABUFFER_PARAM_UVEC2

// The parameters as one std140 uniform block with an instance name, so its
// members are not globals of the host's shader: `habuffer_params.table_size`,
// spelled ha_table_size (a macro) in the shared sources. A host shader needs
// no uniforms of ours, only our buffers bound.
std::string parameter_block() {
  std::string block = "layout(std140, binding = HABUFFER_BINDING_PARAMS) uniform HabufferParams {\n";
  std::string names;
  for (const ParamField& f : kParamFields) {
    // The member is the name without its owner's prefix (habuffer_, ha_, ll_, kb_).
    const std::string name(f.name), member = name.substr(name.find('_') + 1);
    block += "  " + std::string(f.type) + " " + member + ";\n";
    names += "#define " + std::string(f.name) + " habuffer_params." + member + "\n";
  }
  return block + "} habuffer_params;\n" + names;
}

// "HABUFFER_BINDING_HEADS" for GlBindings::Point "heads".
std::string binding_macro(const char* name) {
  std::string macro = std::string("HABUFFER_BINDING_") + name;
  std::transform(macro.begin(), macro.end(), macro.begin(), [](unsigned char c) { return std::toupper(c); });
  return macro;
}

}  // namespace

ModuleVariant ModuleVariant::resolved(AtomicMode mode, const GlInfo& info) const {
  ModuleVariant v = *this;
  if (!v.slot_read_first) v.slot_read_first = mode == AtomicMode::Emulated64;
  if (!v.max_age_read_first) v.max_age_read_first = info.software_rasterizer;
  return v;
}

std::string ModuleVariant::defines() const {
  std::string s;
  if (count_writes) s += "#define HABUFFER_COUNT_WRITES\n";
  if (slot_read_first) s += "#define HABUFFER_SLOT_READ_FIRST " + std::string(*slot_read_first ? "1" : "0") + "\n";
  if (max_age_read_first)
    s += "#define HABUFFER_MAX_AGE_READ_FIRST " + std::string(*max_age_read_first ? "1" : "0") + "\n";
  return s;
}

std::string ModuleVariant::str() const {
  const auto choice = [](std::optional<bool> b) { return !b ? "auto" : *b ? "1" : "0"; };
  return std::string("count_writes=") + (count_writes ? "1" : "0") + " slot_read_first=" + choice(slot_read_first) +
         " max_age_read_first=" + choice(max_age_read_first);
}

std::span<const GlBindings::Point> GlBindings::points() {
  static constexpr Point kPoints[] = {
      {"counters", &GlBindings::counters, 0},  {"locks", &GlBindings::locks, 0},
      {"capture", &GlBindings::capture, 0},    {"stream", &GlBindings::stream, 0},
      {"deferred", &GlBindings::deferred, 0},  {"saturation", &GlBindings::saturation, 0},
      {"table", &GlBindings::table, 1},        {"max_age", &GlBindings::max_age, 1},
      {"offsets", &GlBindings::offsets, 1},    {"heads", &GlBindings::heads, 2},
      {"nodes", &GlBindings::nodes, 2},        {"links", &GlBindings::links, 2},
      {"counts", &GlBindings::counts, 3},      {"layers", &GlBindings::layers, 3},
      {"slots", &GlBindings::slots, 4},        {"occupancy", &GlBindings::occupancy, 4},
      {"limits", &GlBindings::limits, 4},      {"accum", &GlBindings::accum, 5},
      {"revealage", &GlBindings::revealage, 5}};
  return kPoints;
}

std::vector<unsigned> GlBindings::storage_points() const {
  std::vector<unsigned> out;
  for (const Point& p : points()) out.push_back(this->*p.member);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void GlBindings::validate() const {
  const auto all = points();
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      const bool together = all[i].group == 0 || all[j].group == 0 || all[i].group == all[j].group;
      if (together && this->*all[i].member == this->*all[j].member)
        throw GlError(std::string("shader-storage binding point ") + std::to_string(this->*all[i].member) +
                      " is used twice (GlBindings::" + all[i].name + " and ::" + all[j].name + ")");
    }
  GLint max_storage = 0, max_uniform = 0;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &max_storage);
  glGetIntegerv(GL_MAX_UNIFORM_BUFFER_BINDINGS, &max_uniform);
  // Points run from 0 to the limit - 1: a point equal to the limit is out.
  for (const Point& p : all)
    if (this->*p.member >= static_cast<unsigned>(max_storage))
      throw GlError(std::string("shader-storage binding point GlBindings::") + p.name + " = " +
                    std::to_string(this->*p.member) +
                    " is beyond this context's GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS (" + std::to_string(max_storage) +
                    ": points 0.." + std::to_string(max_storage - 1) + ")");
  if (params >= static_cast<unsigned>(max_uniform))
    throw GlError("uniform-buffer binding point GlBindings::params = " + std::to_string(params) +
                  " is beyond this context's GL_MAX_UNIFORM_BUFFER_BINDINGS (" + std::to_string(max_uniform) +
                  ": points 0.." + std::to_string(max_uniform - 1) + ")");
}

GlBindings GlBindings::from_base(unsigned storage_base, unsigned uniform_base) {
  GlBindings b;
  unsigned shared = storage_base + kTechniquePoints;
  unsigned group = 0, next = storage_base;
  for (const Point& p : points()) {
    if (p.group == 0) {
      b.*p.member = shared++;
      continue;
    }
    if (p.group != group) next = storage_base;  // each technique's buffers from the base
    group = p.group;
    b.*p.member = next++;
  }
  b.params = uniform_base;
  return b;
}

std::string GlBindings::glsl_defines(bool overridable) const {
  std::string s;
  const auto define = [&](const char* name, unsigned v) {
    const std::string macro = binding_macro(name);
    if (overridable) s += "#ifndef " + macro + '\n';
    s += "#define " + macro + ' ' + std::to_string(v) + '\n';
    if (overridable) s += "#endif\n";
  };
  for (const Point& p : points()) define(p.name, this->*p.member);
  define("params", params);
  return s;
}

namespace {

// The binding names a file of technique group `group` reads: its own
// buffers', the shared ones and PARAMS, as "HABUFFER_BINDING_TABLE MAX_AGE ...".
std::string binding_names(unsigned group) {
  std::string own, shared;
  for (const GlBindings::Point& p : GlBindings::points()) {
    if (p.group != 0 && p.group != group) continue;
    std::string& list = p.group == 0 ? shared : own;
    const std::string name = binding_macro(p.name).substr(std::string("HABUFFER_BINDING_").size());
    list += (list.empty() ? "" : " ") + name;
  }
  return "HABUFFER_BINDING_" + own + " " + shared + " PARAMS";
}

// For the installed files (overridable points): a host that defines another
// technique's binding names but none of this technique's own gets one
// #error naming the names to define. Each technique's buffers have names of
// their own, so a host that moved TABLE before the lists' file would
// otherwise leave the lists at the defaults while the container it made
// with moved GlBindings::heads bound elsewhere, and every fragment vanished.
std::string own_binding_guard(unsigned group) {
  std::string others, own, own_list;
  for (const GlBindings::Point& p : GlBindings::points()) {
    if (p.group == 0) continue;
    const std::string macro = binding_macro(p.name);
    if (p.group == group) {
      own += (own.empty() ? "" : " || ") + std::string("defined(") + macro + ")";
      own_list += (own_list.empty() ? "" : ", ") + macro;
    } else {
      others += (others.empty() ? "" : " || ") + std::string("defined(") + macro + ")";
    }
  }
  return "#if (" + others + ") && !(" + own + ")\n#error the buffers of this technique are bound at " + own_list +
         ": define those (the binding names of another technique do not move them)\n#endif\n";
}

}  // namespace

std::string module_extensions(AtomicMode mode) { return mode_extensions(mode); }

std::string technique_module_body(Technique technique, AtomicMode mode, const GlBindings& bindings, ShaderStage stage,
                                  bool overridable_bindings) {
  std::string s;
  if (stage == ShaderStage::Fragment) s += "#define HABUFFER_STAGE_FRAGMENT\n";
  if (overridable_bindings) s += own_binding_guard(gl_descriptor(technique).binding_group);
  s += bindings.glsl_defines(overridable_bindings);
  s += word_defines(mode);
  s += kHaConstants;
  s += '\n';
  s += parameter_block();
  for (const char* part : {kGlslEnv, kEntryCommon}) {
    s += part;
    s += '\n';
  }
  return s + gl_descriptor(technique).module_parts(mode);
}

std::string technique_module(Technique technique, AtomicMode mode, const GlBindings& bindings, ShaderStage stage,
                             std::string_view header) {
  std::string s = "#version 450 core\n";
  s += mode_extensions(mode);
  s += header;
  if (!header.empty() && header.back() != '\n') s += '\n';
  return s + technique_module_body(technique, mode, bindings, stage);
}

std::string ha_module(AtomicMode mode, const GlBindings& bindings, ShaderStage stage, std::string_view header) {
  return technique_module(Technique::Ha, mode, bindings, stage, header);
}

std::string insert_stream_compute(Technique technique, AtomicMode mode, const GlBindings& bindings) {
  return technique_module(technique, mode, bindings, ShaderStage::Compute) + kInsertStreamCompute;
}

std::string insert_stream_compute(AtomicMode mode, const GlBindings& bindings) {
  return insert_stream_compute(Technique::Ha, mode, bindings);
}

std::string resume_compute(AtomicMode mode, const GlBindings& bindings) {
  return resume_compute(Technique::Ha, mode, bindings);
}

std::string resume_compute(Technique technique, AtomicMode mode, const GlBindings& bindings) {
  return technique_module(technique, mode, bindings, ShaderStage::Compute) + kResumeCompute;
}

std::string kbuffer_count_compute(AtomicMode mode, const GlBindings& bindings) {
  return technique_module(Technique::KBuffer, mode, bindings, ShaderStage::Compute) + kKBufferCountCompute;
}

std::string sort_compute(Technique technique, AtomicMode mode, const GlBindings& bindings) {
  if (descriptor(technique).sorted_on_insert)
    throw GlError("technique " + to_string(technique) + " is sorted by insertion: it has no sort pass");
  return technique_module(technique, mode, bindings, ShaderStage::Compute) + kSortCompute;
}

std::string full_screen_vertex() { return std::string("#version 450 core\n") + kFullScreenVertex; }

std::string clear_pass_fragment(AtomicMode mode, const GlBindings& bindings) {
  return ha_module(mode, bindings, ShaderStage::Fragment) + kClearPassFragment;
}

std::string resolve_fragment(Technique technique, AtomicMode mode, const GlBindings& bindings) {
  return resolve_fragment(technique, mode, bindings, 1, SampleResolve::Pixel);
}

std::string resolve_fragment(Technique technique, AtomicMode mode, const GlBindings& bindings, std::uint32_t samples,
                             SampleResolve how) {
  std::string header = "#define HABUFFER_RESOLVE_PASS\n";
  if (samples > 1)
    header += how == SampleResolve::Pixel
                  ? "#define HABUFFER_RESOLVE_PIXEL\n"
                  : "#define HABUFFER_RESOLVE_SAMPLE\nuint habuffer_resolve_sample() { return uint(gl_SampleID); }\n";
  return technique_module(technique, mode, bindings, ShaderStage::Fragment, header) + kResolveFragment;
}

std::pair<std::string, std::string> insert_stream_points(Technique technique, AtomicMode mode,
                                                         const GlBindings& bindings) {
  // The vertex stage takes the compute module for HaFragment and the parameters.
  return {technique_module(technique, mode, bindings, ShaderStage::Compute) + kPointStreamVertex,
          technique_module(technique, mode, bindings, ShaderStage::Fragment) + kPointStreamFragment};
}

std::string resolve_fragment(AtomicMode mode, const GlBindings& bindings) {
  return resolve_fragment(Technique::Ha, mode, bindings);
}

std::vector<ShaderSource> library_shaders(AtomicMode mode, const GlBindings& bindings) {
  std::vector<ShaderSource> shaders;
  for (const TechniqueDescriptor* d : technique_registry()) {
    // The hash table's passes keep their historical names ("insert", "resolve").
    const std::string name = d->capacity == CapacityKind::TableSlots ? "" : std::string(d->name) + "-";
    if (d->stores_lists) {
      shaders.push_back({name + "insert", "comp", insert_stream_compute(d->technique, mode, bindings)});
      if (!d->sorted_on_insert) shaders.push_back({name + "sort", "comp", sort_compute(d->technique, mode, bindings)});
    } else {
      const auto [vertex, fragment] = insert_stream_points(d->technique, mode, bindings);
      shaders.push_back({name + "insert", "vert", vertex});
      shaders.push_back({name + "insert", "frag", fragment});
    }
    shaders.push_back({name + "resolve", "frag", resolve_fragment(d->technique, mode, bindings)});
    if (d->stores_lists) {  // the multisampled resolves (4 samples; the sample count is a parameter)
      shaders.push_back({name + "resolve-msaa-pixel", "frag",
                         resolve_fragment(d->technique, mode, bindings, 4, SampleResolve::Pixel)});
      shaders.push_back({name + "resolve-msaa-sample", "frag",
                         resolve_fragment(d->technique, mode, bindings, 4, SampleResolve::Sample)});
    }
    if (const auto own = gl_descriptor(d->technique).own_shaders) {
      std::vector<ShaderSource> more = own(mode, bindings);
      shaders.insert(shaders.end(), more.begin(), more.end());
    }
  }
  return shaders;
}

}  // namespace habuffer::gl

namespace habuffer::gl {

namespace {

// The light lookup for file-based pipelines (gl/shadow_lookup.h): its
// binding points overridable, after a technique file of the same mode.
std::string light_lookup_file(AtomicMode mode) {
  return "// habuffer " HABUFFER_VERSION ": translucent shadows' light lookup, atomic mode " + to_string(mode) +
         ".\n"
         "// Place after a technique file of the same mode (it needs its constants), then call\n"
         "//   float habuffer_shadow_transmittance(vec3 world_point)\n"
         "//   float habuffer_shadow_transmittance(uvec2 light_pixel, float light_depth)\n"
         "// with the light buffer bound as habuffer::gl::GlShadowLookup binds it (or the block HabufferLight\n"
         "// written by the host with its own light matrices). Binding points: #define any of\n"
         "//   HABUFFER_LIGHT_BINDING_TABLE MAX_AGE OFFSETS (shader-storage) PARAMS (uniform)\n"
         "// before this file to move them, with the same numbers as habuffer::gl::GlLightBindings.\n" +
         light_lookup_part(GlLightBindings{}, mode, true);
}

// The spatial hash's lookup for file-based pipelines (gl_spatial_hash.h):
// one file for every mode (it reads slots as uvec2), points overridable.
std::string spatial_lookup_file() {
  return "// habuffer " HABUFFER_VERSION ": the spatial hash's lookup (habuffer::gl::GlSpatialHash), for any shader\n"
         "// stage and any atomic mode (no 64-bit integers needed). Place after `#version 450 core`, at global\n"
         "// scope (beside a technique file or without one), then call\n"
         "//   bool habuffer_spatial_find(uvec3 key, out uint stored)       // the rule's encoding, as GlSpatialHash::find\n"
         "//   bool habuffer_spatial_find_value(uvec3 key, out uint value)  // decoded, as SpatialHash::find\n"
         "// with the table bound by GlSpatialHash::bind_for_lookup(). Binding points: #define any of\n"
         "//   HABUFFER_SPATIAL_BINDING_TABLE MAX_AGE OFFSETS (shader-storage) PARAMS (uniform)\n"
         "// before this file to move them, with the same numbers as habuffer::gl::GlSpatialBindings.\n"
         "// Reserved names: sh_*, habuffer_spatial*, HabufferSpatial*, HABUFFER_SPATIAL_*, HABUFFER_SH_*.\n" +
         spatial_lookup_part(GlSpatialBindings{}, true);
}

}  // namespace

std::vector<GlslFile> host_glsl_files() {
  const GlBindings defaults;
  std::vector<GlslFile> files;
  for (AtomicMode mode : {AtomicMode::Native32, AtomicMode::Native64, AtomicMode::Emulated64}) {
    const std::string dir = to_string(mode) + "/";
    const std::string layout = mode == AtomicMode::Native32 ? "L32" : "L64";
    files.push_back({dir + "extensions.glsl",
                     "// habuffer " HABUFFER_VERSION ": the #extension lines of atomic mode " + to_string(mode) +
                         ", right after the shader's #version 450 line and before any code.\n" +
                         module_extensions(mode)});
    for (Technique t : all_techniques())
      for (ShaderStage stage : {ShaderStage::Fragment, ShaderStage::Compute}) {
        const bool fragment = stage == ShaderStage::Fragment;
        if (!fragment && !stores_lists(t)) continue;  // the blended baselines need the blender: fragment shaders only
        std::string head = "// habuffer " HABUFFER_VERSION ": technique " + to_string(t) + ", atomic mode " +
                           to_string(mode) + " (" + layout + " records), for " +
                           (fragment ? "fragment" : "compute") + " shaders.\n";
        head +=
            "// Place after `#version 450 core` and the lines of extensions.glsl, anywhere at global scope\n"
            "// (after the host's own declarations too), then call\n"
            "//   uint habuffer_insert(uvec2 pixel, float depth, uint rgba)  // rgba: packUnorm4x8, straight alpha\n"
            "// once per fragment. Binding points (defaults: this technique's own buffers from 16, the shared\n"
            "// ones 19..24, uniform 16): #define any of\n"
            "//   " + binding_names(gl_descriptor(t).binding_group) + "\n"
            "// before this file to move them, with the same numbers as the host's habuffer::gl::GlBindings\n"
            "// (GlBindings::glsl_defines() writes them). Another technique's names do not move this one's\n"
            "// buffers: defining only those is an #error.\n"
            "// Reserved names: ha_*, Ha*, habuffer_*, HABUFFER_*, ll_*, fa_*, sl_*, kb_*, bl_*, wb_*.\n";
        if (!stores_lists(t))
          head +=
              "// This technique blends: it declares `out vec4 ha_blended_accum` at location 0 (wboit also\n"
              "// ha_blended_revealage at 1; declare no outputs of your own there). Call habuffer_insert at most once\n"
              "// per invocation with the invocation's own pixel (habuffer_insert_here), discard where you call none,\n"
              "// and draw into the technique's gather_framebuffer() (the frame driver binds it and the blend\n"
              "// setup around your gather).\n";
        files.push_back({dir + to_string(t) + (fragment ? ".frag.glsl" : ".comp.glsl"),
                         head + technique_module_body(t, mode, defaults, stage, true)});
      }
    if (mode != AtomicMode::Native32) files.push_back({dir + "light_lookup.glsl", light_lookup_file(mode)});
  }
  files.push_back({"spatial_lookup.glsl", spatial_lookup_file()});
  return files;
}

}  // namespace habuffer::gl
