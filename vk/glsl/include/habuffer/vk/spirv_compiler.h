/// @file
/// GLSL to SPIR-V for Vulkan at run time, through glslang (libglslang): the
/// library's own passes and a host's variants are assembled from the same
/// shared GLSL text the CPU and OpenGL run, then compiled here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace habuffer::vk {

/// The stage of a shader to compile.
enum class SpirvStage { Compute, Vertex, Fragment };

/// SPIR-V 1.5 for Vulkan 1.2 of a complete GLSL shader (its #version line
/// first). Throws VulkanError naming `name` with glslang's log when it does
/// not compile.
std::vector<std::uint32_t> compile_to_spirv(const std::string& source, SpirvStage stage, const std::string& name);

}  // namespace habuffer::vk
