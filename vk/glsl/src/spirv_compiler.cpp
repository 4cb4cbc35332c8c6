#include "habuffer/vk/spirv_compiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <mutex>

#include "habuffer/vk/vulkan_error.h"

namespace habuffer::vk {
namespace {

EShLanguage language(SpirvStage stage) {
  switch (stage) {
    case SpirvStage::Compute: return EShLangCompute;
    case SpirvStage::Vertex: return EShLangVertex;
    case SpirvStage::Fragment: return EShLangFragment;
  }
  return EShLangCompute;
}

// glslang's process-wide tables, made once (never finalized: other users of
// glslang in the process may still compile).
void initialize_once() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

// The log's first lines, enough to name the error without the whole shader.
std::string first_lines(const std::string& log, std::size_t lines) {
  std::size_t end = 0;
  for (std::size_t i = 0; i < lines && end != std::string::npos; ++i) {
    end = log.find('\n', end == 0 ? 0 : end + 1);
  }
  return end == std::string::npos ? log : log.substr(0, end);
}

}  // namespace

std::vector<std::uint32_t> compile_to_spirv(const std::string& source, SpirvStage stage, const std::string& name) {
  initialize_once();
  const EShLanguage lang = language(stage);
  glslang::TShader shader(lang);
  const char* text = source.c_str();
  const char* names = name.c_str();
  shader.setStringsWithLengthsAndNames(&text, nullptr, &names, 1);
  shader.setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  if (!shader.parse(GetDefaultResources(), 450, false, messages))
    throw VulkanError(name + " does not compile for Vulkan: " + first_lines(shader.getInfoLog(), 6));
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages))
    throw VulkanError(name + " does not link for Vulkan: " + first_lines(program.getInfoLog(), 6));
  std::vector<std::uint32_t> spirv;
  glslang::SpvOptions options;
  options.validate = true;
  spv::SpvBuildLogger logger;
  glslang::GlslangToSpv(*program.getIntermediate(lang), spirv, &logger, &options);
  if (const std::string log = logger.getAllMessages(); log.find("error") != std::string::npos)
    throw VulkanError(name + ": SPIR-V generation failed: " + first_lines(log, 6));
  return spirv;
}

}  // namespace habuffer::vk
