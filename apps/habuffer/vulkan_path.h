/// @file
/// Whether this CLI has the Vulkan path (--path vk): built where
/// habuffer::vk is (apps/CMakeLists.txt defines HABUFFER_WITH_VK), so the
/// commands declare the alternative in one expression each.
#pragma once

namespace habuffer::cli {

#ifdef HABUFFER_WITH_VK
inline constexpr bool kHasVulkanPath = true;
#else
inline constexpr bool kHasVulkanPath = false;
#endif

}  // namespace habuffer::cli
