/// @file
/// A frame driver's module fingerprint (HABUFFER_MODULE_ID): insert calls
/// from a shader built from another driver's module text count as foreign
/// (HABUFFER_COUNTER_FOREIGN) and make the frame refuse them. One rule for
/// the OpenGL and the Vulkan frame drivers.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace habuffer::gl {

/// FNV-1a of the module text without its fingerprint define (never 0: the
/// parameter block's 0 means no driver wrote it).
std::uint32_t module_fingerprint(std::string_view module_text);
/// "#define HABUFFER_MODULE_ID 0x%08xu\n" of `id`, the line a driver's
/// module_source() puts before the host's header.
std::string module_id_define(std::uint32_t id);

}  // namespace habuffer::gl
