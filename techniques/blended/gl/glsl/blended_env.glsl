// The blended baselines on the GPU (techniques/blended/cpu/include/habuffer/techniques/blended/blended.glsl):
// no lists, each fragment blended into per-pixel accumulators by the
// fixed-function blender in primitive order, the only order-keeping
// accumulation a GPU has (wboit's sums would also go through float atomics,
// which core GL lacks). The insert call writes the fragment's term to the
// fragment outputs, and the container's framebuffer (bound by the frame
// driver around the gather) blends it:
//   blend:  output 0 (a c, a), colour (ONE, ONE_MINUS_SRC_ALPHA), alpha
//           (ZERO, ONE_MINUS_SRC_ALPHA): C = a c + (1 - a) C, T = (1 - a) T;
//   wboit:  output 0 wb_accum_term, (ONE, ONE); output 1 (a), revealage
//           (ZERO, ONE_MINUS_SRC_COLOR): r = (1 - a) r.
// Every habuffer_insert call first zeroes the outputs (a call that blends nothing
// leaves the pixel as it was), so a host shader calls habuffer_insert at most once
// per invocation and discards where it calls none. After the gather the
// container copies the attachments into its storage buffers, which the
// resolve reads. Outputs are declared in fragment modules except the
// resolve's (HABUFFER_RESOLVE_PASS), at locations 0 and 1, the container's
// draw buffers 0 and 1. A call blends at the invocation's own pixel: one
// that names another pixel blends nothing and counts invalid.
#if defined(HABUFFER_STAGE_FRAGMENT) && !defined(HABUFFER_RESOLVE_PASS)
#define HABUFFER_BLENDED_OUTPUTS
layout(location = 0) out vec4 ha_blended_accum;
#ifdef HABUFFER_WBOIT
layout(location = 1) out vec4 ha_blended_revealage;
#endif
#endif

layout(std430, binding = HABUFFER_BINDING_ACCUM) readonly buffer HaAccum { vec4 ha_accum[]; };
layout(std430, binding = HABUFFER_BINDING_REVEALAGE) readonly buffer HaRevealage { float ha_revealage[]; };
