/// @file
/// The GPU path's parameter block, declared once for C++ and GLSL (as
/// nvpro-samples' common.h does): the reader defines HABUFFER_PARAMS_BEGIN,
/// HABUFFER_PARAMS_END and HABUFFER_PARAM_UINT / HABUFFER_PARAM_FLOAT / HABUFFER_PARAM_UVEC2 before
/// including it (habuffer/technique_params.h: the C++ struct ParamBlock, which
/// the GL path uploads as GlParams; prelude assembly: a std140 uniform block,
/// whose members are GLSL globals). Keep every uvec2 at an offset that is a
/// multiple of 8 (std140); technique_params.h checks the offsets and size.
// No include guard: an X-macro list, expanded once per reader.

HABUFFER_PARAMS_BEGIN
  HABUFFER_PARAM_UVEC2(ha_table_size)          // HA-buffer: the table H
  HABUFFER_PARAM_UINT(habuffer_age_bits)             // every technique: the depth code's bits (SPEC 2)
  HABUFFER_PARAM_UINT(ha_block)                // HA-buffer: max-age block B
  HABUFFER_PARAM_UINT(ha_max_age_cells_x)      // HA-buffer: max-age cells per row
  HABUFFER_PARAM_UINT(habuffer_iter_limit)           // HA-buffer: probes per insert call; sorted and paged lists: tries
  HABUFFER_PARAM_FLOAT(habuffer_cull_tau)            // HA-buffer: early cull (0: off)
  HABUFFER_PARAM_UINT(habuffer_lock_spin_limit)      // HA-buffer, emulated64: busy attempts before a call is cut short
  HABUFFER_PARAM_UVEC2(habuffer_screen_size)         // every technique
  HABUFFER_PARAM_UINT(habuffer_capture_capacity)     // fragments the capture buffer holds; 0: capture off
  HABUFFER_PARAM_UINT(habuffer_capture_only)         // 1: capture, insert nothing, count nothing
  HABUFFER_PARAM_UINT(habuffer_deferred_capacity)    // HA-buffer: calls cut short that the deferred-call buffer holds
  HABUFFER_PARAM_UINT(ll_pool_capacity)        // pool techniques: nodes
  HABUFFER_PARAM_UINT(habuffer_layers)               // fixed arrays, k-buffer: K
  HABUFFER_PARAM_UINT(habuffer_saturation)           // HA-buffer, sorted lists: 1: saturation depth (with early cull)
  HABUFFER_PARAM_UINT(habuffer_gather_phase)         // HABUFFER_PHASE_*: 0 inserting, 1 the k-buffer's fill, 2 counting
  HABUFFER_PARAM_UINT(kb_occupancy_culling)            // k-buffer: 1: occupancy-map culling
  HABUFFER_PARAM_UINT(kb_occupancy_words)      // k-buffer: 32-bit words of a pixel's map
  HABUFFER_PARAM_UINT(kb_occupancy_near_code)  // k-buffer: the depth code of the range's near end
  HABUFFER_PARAM_UINT(kb_occupancy_bucket_codes)  // k-buffer: depth codes per bucket
  HABUFFER_PARAM_FLOAT(habuffer_depth_near)         // wboit: the depth range its weights span
  HABUFFER_PARAM_FLOAT(habuffer_depth_far)
  HABUFFER_PARAM_UINT(habuffer_depth_reversed)       // every technique: 1: habuffer_insert_here reads 1 - gl_FragCoord.z (reversed-Z)
  HABUFFER_PARAM_UINT(habuffer_light_gather)        // every technique: 1: a light pass (GlFrameOptions::light), depths are its t
  HABUFFER_PARAM_FLOAT(habuffer_light_near)         // the light's eye distances of t = 0 and t = 1 (habuffer_insert_light)
  HABUFFER_PARAM_FLOAT(habuffer_light_far)
  HABUFFER_PARAM_FLOAT(habuffer_light_a)            // the light's t of window depth z: (a z + b) / (c z + d) (GlLightDepthMap)
  HABUFFER_PARAM_FLOAT(habuffer_light_b)
  HABUFFER_PARAM_FLOAT(habuffer_light_c)
  HABUFFER_PARAM_FLOAT(habuffer_light_d)
  HABUFFER_PARAM_UINT(habuffer_module_id)           // the frame driver's module fingerprint (HABUFFER_MODULE_ID of its module_source)
  HABUFFER_PARAM_UINT(habuffer_coverage_bits)        // every technique: C, the samples of a multisampled screen (0: one)
  HABUFFER_PARAM_UINT(habuffer_stop_at_failure)     // HA-buffer: 1: a lossless attempt to be gathered again stops inserting at its first failure (HABUFFER_COUNTER_FAILED_ONCE)
  HABUFFER_PARAM_UINT(ha_unused_1)                  // std140 rounds the block to 16 bytes
  HABUFFER_PARAM_UINT(ha_unused_2)
HABUFFER_PARAMS_END
