#include "habuffer/vk/vulkan_glsl.h"

#include <stdexcept>

#include "habuffer/technique_descriptor.h"
#include "vulkan_glsl_sources.h"

namespace habuffer::vk {

gl::GlBindings vulkan_bindings() { return gl::GlBindings::from_base(1, 0); }

std::string vulkan_module_extensions(AtomicMode mode) {
  switch (mode) {
    case AtomicMode::Native32: return "";
    case AtomicMode::Native64:
      return "#extension GL_ARB_gpu_shader_int64 : require\n#extension GL_EXT_shader_atomic_int64 : require\n";
    case AtomicMode::Emulated64: return "#extension GL_ARB_gpu_shader_int64 : require\n";
  }
  return "";
}

std::string vulkan_device_defines(bool lavapipe) {
  return lavapipe ? "#define HABUFFER_BUFFER_FENCE()\n" : "";
}

std::string vulkan_technique_module(Technique technique, AtomicMode mode, gl::ShaderStage stage,
                                    std::string_view header) {
  std::string s = "#version 450 core\n" + vulkan_module_extensions(mode);
  s += header;
  if (!header.empty() && header.back() != '\n') s += '\n';
  return s + gl::technique_module_body(technique, mode, vulkan_bindings(), stage);
}

std::string vulkan_insert_stream_compute(Technique technique, AtomicMode mode, std::string_view variant_defines) {
  return vulkan_technique_module(technique, mode, gl::ShaderStage::Compute, variant_defines) +
         gl::kInsertStreamCompute;
}

std::string vulkan_sort_compute(Technique technique, AtomicMode mode, std::string_view variant_defines) {
  if (descriptor(technique).sorted_on_insert)
    throw std::invalid_argument("technique " + to_string(technique) + " is sorted by insertion: it has no sort pass");
  return vulkan_technique_module(technique, mode, gl::ShaderStage::Compute, variant_defines) + gl::kSortCompute;
}

std::string vulkan_resume_compute(Technique technique, AtomicMode mode, std::string_view variant_defines) {
  return vulkan_technique_module(technique, mode, gl::ShaderStage::Compute, variant_defines) + gl::kResumeCompute;
}

std::string vulkan_resolve_compute(Technique technique, AtomicMode mode, std::uint32_t samples,
                                   std::string_view variant_defines) {
  // The defines of the OpenGL path's per-pixel resolve (gl::resolve_fragment).
  std::string header(variant_defines);
  if (!header.empty() && header.back() != '\n') header += '\n';
  header += "#define HABUFFER_RESOLVE_PASS\n";
  if (samples > 1) header += "#define HABUFFER_RESOLVE_PIXEL\n";
  return vulkan_technique_module(technique, mode, gl::ShaderStage::Compute, header) + kResolveCompute;
}

std::string vulkan_resolve_image_compute(Technique technique, AtomicMode mode, std::string_view image_format,
                                         std::string_view variant_defines) {
  if (image_format != "rgba8" && image_format != "rgba16f" && image_format != "rgba32f")
    throw std::invalid_argument("the resolve writes rgba8, rgba16f or rgba32f images, not \"" +
                                std::string(image_format) + "\"");
  std::string header(variant_defines);
  if (!header.empty() && header.back() != '\n') header += '\n';
  header += "#define HABUFFER_RESOLVE_PASS\n#define HABUFFER_TARGET_FORMAT " + std::string(image_format) + "\n";
  return vulkan_technique_module(technique, mode, gl::ShaderStage::Compute, header) + kResolveImageCompute;
}

}  // namespace habuffer::vk
