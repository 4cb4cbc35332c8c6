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
  HA_PARAM_UINT(ha_layers)               // fixed arrays: K
HA_PARAMS_END

#endif
