/// @file
/// The Vulkan path's own GLSL entries as text, embedded at build time by
/// vk/glsl/CMakeLists.txt (the shared files are gl/glsl's). Private to the part.
#pragma once

namespace habuffer::vk {

extern const char* const kResolveCompute;       ///< vk/glsl/shaders/resolve.comp.glsl: the resolve pass
extern const char* const kResolveImageCompute;  ///< vk/glsl/shaders/resolve_image.comp.glsl: into a host's image

}  // namespace habuffer::vk
