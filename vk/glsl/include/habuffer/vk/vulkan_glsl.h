/// @file
/// The shared GLSL assembled for Vulkan: the same module text the OpenGL
/// path compiles (gl/glsl: the shared sources, the technique's parts, the
/// entries, which declare their counts as push constants where VULKAN is
/// defined), with Vulkan's #extension lines and binding points. Needs no
/// context of either API.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "habuffer/atomic_mode.h"
#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/module_variant.h"
#include "habuffer/technique.h"

namespace habuffer::vk {

/// The Vulkan path's binding points, all in descriptor set 0: the parameter
/// block at 0 (a uniform buffer), every storage buffer from 1 (each
/// technique's own at 1-3, the shared ones at 4-9).
gl::GlBindings vulkan_bindings();

/// The #extension lines `mode` needs on Vulkan ("" for native32; native64:
/// GL_EXT_shader_atomic_int64, which SPIR-V's Int64Atomics capability needs).
std::string vulkan_module_extensions(AtomicMode mode);

/// The defines a module needs on a kind of device, before any other header
/// text: on lavapipe (`lavapipe`: VulkanInfo::lavapipe), HABUFFER_BUFFER_FENCE()
/// defined empty. Lavapipe ends the lanes of a divergent branch that meets a memory
/// barrier (seen as calls without an outcome: sorted lists' links and
/// emulated64's lock publish their writes inside such branches), and its
/// atomics, sequentially consistent operations on host memory, already
/// order the writes before them. "" on any other device.
std::string vulkan_device_defines(bool lavapipe);

/// A complete module for Vulkan: #version, the mode's extensions, `header`
/// (defines: the variant's, a host's), then the module body of every path.
std::string vulkan_technique_module(Technique technique, AtomicMode mode, gl::ShaderStage stage,
                                    std::string_view header = {});

/// The compute entry (a fragment stream in a buffer, its count a push
/// constant) of `technique`'s module with `variant_defines`.
std::string vulkan_insert_stream_compute(Technique technique, AtomicMode mode, std::string_view variant_defines = {});
/// The sort pass of a technique that sorts after the gather (one
/// invocation per pixel, 8x8 groups); std::invalid_argument for one sorted
/// by insertion.
std::string vulkan_sort_compute(Technique technique, AtomicMode mode, std::string_view variant_defines = {});
/// The resume pass of emulated64 (the deferred insert calls at the stream's
/// point, those cut short again appended at the deferred point; their count
/// a push constant).
std::string vulkan_resume_compute(Technique technique, AtomicMode mode, std::string_view variant_defines = {});

/// The resolve pass (SPEC 7) of `technique` on a screen of `samples`
/// samples (a multisampled pixel resolved per pixel, as the CPU's
/// composite_image): one invocation per pixel in 8x8 groups composites its
/// list over its background, in place in a buffer of RGBA floats at the
/// stream's binding point (row 0 at the bottom; rgb the background on entry).
std::string vulkan_resolve_compute(Technique technique, AtomicMode mode, std::uint32_t samples,
                                   std::string_view variant_defines = {});

/// The resolve pass into a host's storage image (set 1, binding 0) of
/// format qualifier `image_format` ("rgba8", "rgba16f", "rgba32f"): each
/// pixel's list composited over the image's texel, in place (colour C + T *
/// texel, alpha (1 - T) + T * texel alpha); texel (x, y) is pixel (x, y).
/// One sample a pixel. std::invalid_argument for another qualifier.
std::string vulkan_resolve_image_compute(Technique technique, AtomicMode mode, std::string_view image_format,
                                         std::string_view variant_defines = {});

}  // namespace habuffer::vk
