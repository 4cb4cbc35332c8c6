// The GPU path's parameter block, declared once for C++ and GLSL (as
// nvpro-samples' common.h does): the reader defines HA_PARAMS_BEGIN,
// HA_PARAMS_END and HA_PARAM_UINT / HA_PARAM_FLOAT / HA_PARAM_UVEC2 before
// including it (gl/gl_params.h: a C++ struct; prelude assembly: a std140
// uniform block, whose members are GLSL globals). Keep every uvec2 at an
// offset that is a multiple of 8 (std140); gl_params.h checks the offsets.
#ifndef HA_PARAMS_H
#define HA_PARAMS_H

HA_PARAMS_BEGIN
  HA_PARAM_UVEC2(ha_table_size)          // HA-buffer: the table H
  HA_PARAM_UINT(ha_age_bits)             // every technique: the depth code's bits (SPEC 2)
  HA_PARAM_UINT(ha_block)                // HA-buffer: max-age block B
  HA_PARAM_UINT(ha_max_age_cells_x)      // HA-buffer: max-age cells per row
  HA_PARAM_UINT(ha_iter_limit)           // HA-buffer: probes per insert call
  HA_PARAM_FLOAT(ha_cull_tau)            // HA-buffer: early cull (0: off)
  HA_PARAM_UINT(ha_lock_spin_limit)      // HA-buffer, emulated64: busy attempts before a call is cut short
  HA_PARAM_UVEC2(ha_screen_size)         // every technique
  HA_PARAM_UINT(ha_capture_capacity)     // fragments the capture buffer holds; 0: capture off
  HA_PARAM_UINT(ha_capture_only)         // 1: capture, insert nothing, count nothing
  HA_PARAM_UINT(ha_count_writes)         // HA-buffer: 1: count slot writes (HA_COUNTER_SLOT_WRITES)
  HA_PARAM_UINT(ha_deferred_capacity)    // HA-buffer: calls cut short that the deferred-call buffer holds
  HA_PARAM_UINT(ha_pool_capacity)        // linked lists: nodes
  HA_PARAM_UINT(ha_layers)               // fixed arrays, k-buffer: K
  HA_PARAM_UINT(ha_saturation)           // HA-buffer, sorted lists: 1: saturation depth (with early cull)
  HA_PARAM_UINT(ha_gather_phase)         // k-buffer: 1 during the occupancy fill pass, else 0
  HA_PARAM_UINT(ha_occupancy)            // k-buffer: 1: occupancy-map culling
  HA_PARAM_UINT(ha_occupancy_words)      // k-buffer: 32-bit words of a pixel's map
  HA_PARAM_UINT(ha_occupancy_near_code)  // k-buffer: the depth code of the range's near end
  HA_PARAM_UINT(ha_occupancy_bucket_codes)  // k-buffer: depth codes per bucket
  HA_PARAM_UINT(ha_params_pad0)          // std140 rounds the block to 16 bytes
  HA_PARAM_UINT(ha_params_pad1)
HA_PARAMS_END

#endif
