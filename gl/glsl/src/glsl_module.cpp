#include <algorithm>
#include <cctype>
#include <span>
#include <string>

#include <epoxy/gl.h>

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/module_variant.h"
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

namespace {

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
    const std::string macro = GlBindings::macro_name(p.name);
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

std::string sort_compute(Technique technique, AtomicMode mode, const GlBindings& bindings) {
  if (descriptor(technique).sorted_on_insert)
    throw GlError("technique " + to_string(technique) + " is sorted by insertion: it has no sort pass");
  return technique_module(technique, mode, bindings, ShaderStage::Compute) + kSortCompute;
}

std::string full_screen_vertex() { return std::string("#version 450 core\n") + kFullScreenVertex; }

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

std::string join_parts(std::initializer_list<const char*> parts) {
  std::string s;
  for (const char* part : parts) {
    s += part;
    s += '\n';
  }
  return s;
}

const char* mode_prelude(AtomicMode mode) { return mode == AtomicMode::Emulated64 ? kPreludeEmulated64 : kPreludeNative; }

}  // namespace habuffer::gl

