/// @file
/// habuffer's OpenGL 4.5 path in one include (with the CPU path's
/// habuffer/habuffer.h): a technique's GPU container (make_gl_technique,
/// GlHaBuffer, ...), the frame driver a host wraps its gather pass in, the
/// GLSL module its shaders include, binding points, the context queries, the
/// light lookup and the spatial hash on the GPU (GlSpatialHash) and, for
/// hosts without a context of their own, a headless EGL context.
#pragma once

#include "habuffer/habuffer.h"

#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/frame_report.h"
#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/techniques/blended/gl_blended_image.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/techniques/arrays/gl_fixed_arrays.h"
#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/gl_spatial_hash.h"
#include "habuffer/gl/techniques/kbuffer/gl_kbuffer.h"
#include "habuffer/gl/techniques/linked_lists/gl_linked_lists.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/host_glsl_files.h"
#include "habuffer/gl/light_mapping.h"
#include "habuffer/gl/shadow_lookup.h"
