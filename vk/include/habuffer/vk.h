/// @file
/// The Vulkan path in one include: the headless context (or a host's device
/// adopted) and what its device offers, the shared GLSL compiled to SPIR-V,
/// compute pipelines, the techniques it runs, the stream build and the frame
/// driver that records into a host's command buffers.
#pragma once

#include "habuffer/vk/compute_pipeline.h"
#include "habuffer/vk/frame_buffers.h"
#include "habuffer/vk/spirv_compiler.h"
#include "habuffer/vk/vulkan_buffer.h"
#include "habuffer/vk/vulkan_build.h"
#include "habuffer/vk/vulkan_context.h"
#include "habuffer/vk/vulkan_error.h"
#include "habuffer/vk/vulkan_frame_driver.h"
#include "habuffer/vk/vulkan_glsl.h"
#include "habuffer/vk/vulkan_info.h"
#include "habuffer/vk/vulkan_registry.h"
#include "habuffer/vk/vulkan_technique.h"
