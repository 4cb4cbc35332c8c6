/// @file
/// The coherent Robin Hood hash on the CPU: the shared GLSL sources of
/// core/{record,hash}/include/habuffer/shared/ compiled as member functions of this class template, with the
/// storage and atomics a GLSL shader would get from its buffers.
///
/// Design
/// ======
///
/// This is the heart of the HA-buffer, and it is written once. The files in
/// shared/ are plain GLSL that is also valid C++ once glsl_env.h has supplied
/// GLSL's types and builtins; HashKernel #includes them inside its class body,
/// so every `ha_*` function becomes a member that reads the "uniforms" below
/// (habuffer_age_bits, ha_table_size, ...) and calls the "buffer" hooks below
/// (ha_atomic_max_slot, ha_load_slot, ...). The GPU path compiles the very same
/// files, with a prelude per atomic mode in place of this class. The CPU and GPU
/// paths therefore cannot drift apart: SPEC 9 demands that they build the same
/// table bit for bit, and the tests check it. The rest of this comment says why
/// the algorithm has the shape it has; the SPEC (docs/specification.md) is the
/// contract and docs/spec-notes.md records the choices it leaves open.
///
/// Record layout (SPEC 2)
/// ----------------------
///
///     L64: | age (A bits) | depth code (32 - A bits) | data (32 bits) |
///     L32: | age (A bits) | depth code (32 - A bits) |
///
/// A record is one unsigned word, most significant field first, and records
/// compare as unsigned integers. That single ordering does all the work:
///
/// - The age, which probe of its pixel's sequence the record sits at (1: its
///   first choice), is in the top bits, so a larger age always wins.
///   `atomicMax(T[s], r)` is the whole Robin Hood decision: the record that has
///   travelled further keeps the slot, the other is handed back as the old
///   value and moves on. At most one atomic per probe (a native atomicMax where
///   the GPU has 64-bit atomics, a slot lock in emulated64, a lock-free
///   compare-exchange loop on the CPU: ha_fetch_max), and the result does not
///   depend on which thread got there first (SPEC 9: insertion is
///   Gale-Shapley deferred acceptance, whose outcome does not depend on the
///   order of proposals).
/// - Between records of the same age, which in one slot means the same pixel
///   (age equivalence, below), the depth code decides. code(t) =
///   (2^D - 1) - min(2^D - 1, floor(t * 2^D)) with D = 32 - A is inverted so
///   that larger means nearer: at equal age a pixel's nearer record wins the
///   slot, and traversal emits a pixel's records nearest first (SPEC 7).
///   t is taken as float32 on both paths and scaled by a power of two, so the
///   code is exact and identical everywhere (ha_depth_code).
/// - Ties of code are broken by the payload (L64's 32-bit data: RGBA8, alpha in
///   the low byte), which makes equal records true duplicates: atomicMax
///   returning r itself is counted as `duplicate` and the call ends.
/// - Ages start at 1, so no record is 0 and 0 can mean an empty slot: every
///   record beats an empty slot, and `old == 0` tells the call it is done.
/// - Age and code together are the high 32 bits in both layouts (ha_high). The
///   read-first check compares only that word: a 64-bit slot read while another
///   invocation writes it may mix halves (emulated 64-bit atomics), but its high
///   half is one value the slot held.
///
/// L32 drops the payload (ha_payload_bits 0) for depth-only uses; the word
/// type is a template parameter so the same code runs on 32- and 64-bit slots.
///
/// Age equivalence (SPEC 4)
/// ------------------------
///
/// The probe of pixel p at age a is h_a(p) = (p + O[a-1]) mod H, with offsets O
/// shared by every pixel (coherent probing: neighbouring pixels probe
/// neighbouring slots, which keeps caches warm). Since the offset depends only
/// on the age, a record of age a in slot s belongs to exactly one pixel,
/// p = (s - O[a-1]) mod H (ha_owner), provided the table is at least the
/// screen on each side (SPEC 1's geometry rule, which BufferConfig enforces).
/// So records store no key at all: the 32 bits a pixel index would take are the
/// payload, and an evicted record's pixel is recovered from where it was found
/// and its age. The same fact is why distinct fragments never tie at a slot:
/// one slot and one age mean one pixel.
///
/// The insert as a step function over the carry
/// --------------------------------------------
///
/// An insert call moves one record at a time: the fragment's, then whichever
/// record it evicts, and so on until a record lands in an empty slot, is a
/// duplicate, is culled, or fails (age beyond AMAX, or the iteration limit).
/// Everything the call knows between two probes is the HabufferCarry of
/// shared/ha_carry.glsl: the carried record r and its pixel p, the age a it is
/// about to try, the probes made (iter), and early cull's accumulated opacity
/// (acc) and last counted front record (front). There is no other state, so
/// shared/ha_insert.glsl is written as a step function over the carry:
/// ha_insert_limit (age first, then iterations, as SPEC 6 orders them), then
/// ha_insert_step_at (one probe: HABUFFER_PENDING while a record must go on,
/// else the outcome of the whole call). Hosts run the steps as they need:
///
/// - ha_insert_run loops until the call ends (the CPU path, and the GPU's first
///   attempt);
/// - the CPU path's owner-computes mode hands a pending carry to the thread
///   that owns its next slot, so no slot is ever written by two threads;
/// - the GPU path defers a call that was cut short (HABUFFER_CUT: an emulated
///   atomic gave up on a contended lock, or the driver's loop budget ended the
///   loop) by writing its carry to the deferred-call buffer, HaDeferred in
///   gl/glsl/shaders/ha_entry.glsl (std430, 40 bytes a call), and the frame's resume
///   pass picks it up exactly where it stopped. Because the carry is the whole
///   call, a resumed call is the same call, and nothing is lost.
///
/// Each probe first reads the slot's high word and skips the atomic when the
/// slot is already larger than the carried record (slots only grow during a
/// gather, so the atomic would change nothing); with early cull a slot of the
/// carried age still takes the atomic, because its opacity is needed.
///
/// Early cull (SPEC 6, L64 with colour only) uses the order again: a slot record
/// of the carried age that beats r is the same pixel's and nearer, so its alpha
/// is accumulated into acc; once acc > tau the carried record is hidden and the
/// call ends `culled`. ha_front_is_new counts each front record at most once
/// under concurrency. With saturation on, the culled depth is kept per pixel
/// and later fragments strictly behind it are rejected before insertion.
///
/// The max-age table (SPEC 5) and early termination
/// ------------------------------------------------
///
/// A pixel's records lie at ages 1, 2, ... of its probe sequence, but the
/// traversal cannot know how far to look without a bound. M keeps one 32-bit
/// cell per B x B block of pixels (B = 8 by default) holding the largest age at
/// which any record of the block's pixels was placed this frame; a placement
/// raises its cell by atomic max (skipped where the cell already reads at or
/// above the age: cells only grow in a gather). Traversal reads ages
/// 1..M[cell(p)] and stops early at the first slot whose record is younger than
/// the age probed (SPEC 7; the paper's Proposition A: no record of p lies
/// beyond). A block rather than a pixel keeps M at 4 bytes per 64 pixels while
/// staying a valid bound for every pixel in it; cells are 32-bit on both paths
/// because the GPU's atomics are, so max-age dumps compare bit for bit.
/// ha_div_block divides by B with a multiply (FastDivisor), since a hardware
/// divide per placement costs more than the probe.
///
/// Why the constants are what they are (shared/ha_constants.h, ha_params.h)
/// ----------------------------------------------------------------------
///
/// - HABUFFER_DEFAULT_AGE_BITS 8: SPEC 2's default, AMAX = 255 probes per record
///   and 24-bit depth codes. HABUFFER_MIN_AGE_BITS 4 .. HABUFFER_MAX_AGE_BITS
///   12 is the range SPEC 2 requires; 12 still leaves 20 bits of depth. The
///   shifts 1u << A and 1u << (32 - A) must stay below 32 (asserted below).
/// - HABUFFER_DEFAULT_BLOCK 8: SPEC 5's block, the paper's 8x8.
/// - HABUFFER_DEFAULT_ITER_LIMIT 65536: SPEC 6's LIMIT, far beyond the few dozen
///   probes ordinary loads need; it only stops pathological calls.
/// - HABUFFER_MAX_ITER_LIMIT 268431359 = 4096 * 65535 - 1: the GPU path first
///   ran probes in at most 65535 chunks of 4096, below llvmpipe's loop cut
///   (commit 63b9d85). Deferral has since replaced the chunks, and the bound is
///   kept on both paths so they accept the same --iter-limit. It also keeps
///   HabufferCarry's 32-bit iter from wrapping (asserted below).
/// - HABUFFER_DEFAULT_LOCK_SPIN_LIMIT 2^24: how long an emulated 64-bit atomic
///   tries a busy slot lock before the call is cut short and deferred; long
///   enough to outlast a lock holder the OS preempted.
/// - HABUFFER_LOCK_SHIFT 3: one lock word per 8 slots in emulated64 (0.5 byte a
///   slot instead of 4), which keeps the GPU HA-buffer below linked lists'
///   memory at load 0.8; a critical section takes one lock, so sharing cannot
///   deadlock.
/// - HABUFFER_COUNTER_STRIDE 16 words (a 64-byte cache line) x
///   HABUFFER_COUNTER_STRIPES 64: the GPU's outcome tallies striped by pixel so
///   a frame's calls do not all hit the same addresses; the GPU-only counters
///   follow the outcomes in each stripe (asserted below).
/// - The outcome codes (HABUFFER_STORED .. HABUFFER_BLENDED) index the counters:
///   exactly one per call (SPEC 11, invariant 1). HABUFFER_PENDING, HABUFFER_CUT
///   and HABUFFER_UNCOUNTED are not outcomes and must not collide with one
///   (asserted below).
/// - HABUFFER_FLOAT_ONE_BITS, HABUFFER_FLOAT_NEG_ZERO_BITS: depth validity is
///   tested on the bit pattern (t in [0, 1] or -0) because shader compilers
///   may assume NaN never happens; the patterns are those of 1.0f and -0.0f
///   (asserted below).
/// - ha_params.h declares the GPU's std140 parameter block once for C++ and
///   GLSL; habuffer/technique_params.h asserts its uvec2 offsets and its size.
#pragma once

#include <atomic>
#include <cstdint>

#include "habuffer/extent.h"
#include "habuffer/glsl_env.h"
#include "habuffer/fast_divisor.h"

namespace habuffer {

// --- constants that must stay in step (see "Why the constants are what they are" above) ---
static_assert(HABUFFER_MIN_AGE_BITS >= 1u && HABUFFER_MAX_AGE_BITS <= 31u,
              "ha_max_age shifts 1u by A and ha_depth_code by 32 - A: both must stay below 32; "
              "change the age-bit range in shared/ha_constants.h only within 1..31");
static_assert(HABUFFER_MIN_AGE_BITS <= HABUFFER_DEFAULT_AGE_BITS && HABUFFER_DEFAULT_AGE_BITS <= HABUFFER_MAX_AGE_BITS,
              "the default age bits must be a legal configuration: keep HABUFFER_DEFAULT_AGE_BITS in "
              "[HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS]");
static_assert(HABUFFER_DEFAULT_ITER_LIMIT >= 1u && HABUFFER_DEFAULT_ITER_LIMIT <= HABUFFER_MAX_ITER_LIMIT,
              "the default iteration limit must be one --iter-limit accepts: keep it in [1, HABUFFER_MAX_ITER_LIMIT]");
static_assert(HABUFFER_MAX_ITER_LIMIT < 0xFFFFFFFFu,
              "HabufferCarry::iter is a 32-bit uint counted up to the limit: "
              "HABUFFER_MAX_ITER_LIMIT must stay below 2^32 - 1");
static_assert(HABUFFER_PENDING >= HABUFFER_OUTCOME_COUNT && HABUFFER_CUT >= HABUFFER_OUTCOME_COUNT &&
                  HABUFFER_UNCOUNTED >= HABUFFER_OUTCOME_COUNT,
              "the step's non-outcomes must not collide with an outcome the counters index: number them from "
              "HABUFFER_OUTCOME_COUNT up in shared/ha_constants.h");
static_assert(HABUFFER_COUNTER_SLOT_WRITES >= HABUFFER_OUTCOME_COUNT,
              "the GPU-only counters follow the outcomes in each stripe: renumber HABUFFER_COUNTER_SLOT_WRITES and "
              "the counters after it from HABUFFER_OUTCOME_COUNT up");
static_assert(HABUFFER_FLOAT_ONE_BITS == std::bit_cast<std::uint32_t>(1.0f) &&
                  HABUFFER_FLOAT_NEG_ZERO_BITS == std::bit_cast<std::uint32_t>(-0.0f),
              "ha_depth_valid tests bit patterns: HABUFFER_FLOAT_ONE_BITS and HABUFFER_FLOAT_NEG_ZERO_BITS must be "
              "those of 1.0f and -0.0f (IEEE-754 binary32)");

/// Everything a kernel reads besides its buffers: the GLSL "uniforms".
struct KernelParams {
  std::uint32_t age_bits = HABUFFER_DEFAULT_AGE_BITS;  ///< A (SPEC 2)
  std::uint32_t coverage_bits = 0;  ///< C: the samples of a multisampled screen, 0 for one
  std::uint32_t payload_bits = 32;  ///< 32 for L64, 0 for L32
  Extent table;  ///< H, in slots
  std::uint32_t block = HABUFFER_DEFAULT_BLOCK;  ///< B, the max-age block side in pixels (SPEC 5)
  std::uint32_t max_age_cells_x = 0;  ///< max-age cells per row
  std::uint32_t iter_limit = HABUFFER_DEFAULT_ITER_LIMIT;  ///< LIMIT of SPEC 6: iterations of one insert call
  float cull_tau = 0.0f;  ///< 0: early cull off
  Extent screen;  ///< V, in pixels
  std::uint32_t* saturation = nullptr;  ///< early cull with saturation: a code per pixel (else nullptr: off)
};

/// Word: std::uint64_t (L64) or std::uint32_t (L32). Concurrent: slots and
/// max-age cells are updated with atomics (several inserters at once); the
/// serial form uses plain loads and stores and must own the table alone.
template <class Word, bool Concurrent>
class HashKernel {
 public:
  /// GLSL's types and builtins (glsl_env.h).
  HABUFFER_GLSL_CLASS_PRELUDE
  /// The slot word.
  using ha_word = Word;
  /// Slot index: 64 bits, so tables above 2^32 slots work.
  using ha_index = std::uint64_t;

  /// Works on the caller's offsets (AMAX of them), table slots and max-age cells
  /// (and params.saturation's image when set); it owns none of them.
  HashKernel(const KernelParams& params, const glm::uvec2* offsets, Word* table, std::uint32_t* max_age)
      : habuffer_age_bits(params.age_bits),
        habuffer_coverage_bits(params.coverage_bits),
        ha_payload_bits(params.payload_bits),
        ha_table_size(params.table.x, params.table.y),
        ha_block(params.block),
        ha_max_age_cells_x(params.max_age_cells_x),
        habuffer_iter_limit(params.iter_limit),
        habuffer_cull_tau(params.cull_tau),
        habuffer_screen_size(params.screen.x, params.screen.y),
        habuffer_saturation(params.saturation != nullptr ? 1u : 0u),
        block_(params.block),
        saturation_(params.saturation),
        offsets_(offsets),
        table_(table),
        max_age_(max_age) {}

  /// --- the environment the shared GLSL expects -----------------------------
  static constexpr uint ha_word_bits = sizeof(Word) * 8;  ///< bits of Word
  uint habuffer_age_bits;  ///< A
  uint habuffer_coverage_bits;  ///< C
  uint ha_payload_bits;  ///< 32 for L64, 0 for L32
  uvec2 ha_table_size;  ///< H
  uint ha_block;  ///< B
  uint ha_max_age_cells_x;  ///< max-age cells per row
  uint habuffer_iter_limit;  ///< LIMIT of SPEC 6
  float habuffer_cull_tau;  ///< 0: early cull off
  uvec2 habuffer_screen_size;  ///< V
  uint habuffer_saturation;  ///< 1: saturation depth on, 0: off

  /// O[i] (SPEC 3).
  uvec2 ha_offset(uint i) const { return offsets_[i]; }

  /// v / B by multiplication: a hardware divide per placement costs more than the probe.
  uint ha_div_block(uint v) const { return block_.div(v); }

  /// atomicMax on slot s: returns the old value, leaves max(old, r).
  Word ha_atomic_max_slot(ha_index s, Word r) { return ha_fetch_max<Concurrent>(table_[s], r); }
  /// CPU atomics always happen (the compare-exchange loop is lock-free).
  static uint ha_atomic_missed() { return 0u; }
  /// Raises max-age cell `cell` to at least `age` (atomic max).
  void ha_atomic_max_age(uint cell, uint age) { ha_fetch_max<Concurrent>(max_age_[cell], age); }
  /// Slot s (a relaxed atomic read when Concurrent).
  Word ha_load_slot(ha_index s) const { return ha_fetch<Concurrent>(table_[s]); }
  /// Max-age cell `cell` (a relaxed atomic read when Concurrent).
  uint ha_load_max_age(uint cell) const { return ha_fetch<Concurrent>(max_age_[cell]); }
  /// The pixel's saturation code (saturation on only).
  uint ha_load_saturation(uint pixel) const { return ha_fetch<Concurrent>(saturation_[pixel]); }
  /// Raises the pixel's saturation code to at least `code` (atomic max).
  void ha_max_saturation(uint pixel, uint code) { ha_fetch_max<Concurrent>(saturation_[pixel], code); }

  /// The table's slots.
  [[nodiscard]] const Word* slots() const { return table_; }

  /// --- the shared algorithm -------------------------------------------------
#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_probe.glsl"
#include "habuffer/shared/ha_carry.glsl"
#include "habuffer/shared/ha_saturation.glsl"
#include "habuffer/shared/ha_insert.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/shared/ha_shadow.glsl"
#include "habuffer/shared/ha_traverse.glsl"

 private:
  FastDivisor block_;
  std::uint32_t* saturation_;
  const glm::uvec2* offsets_;
  Word* table_;
  std::uint32_t* max_age_;
};

// The GPU path defers an insert call cut short by storing its HabufferCarry as HaDeferred (gl/glsl/shaders/ha_entry.glsl:
// std430, 40 bytes: p, a, acc, iter, pad, r and front as 32-bit halves; ha_defer and ha_carry_from copy each field),
// and sizes its buffers by kDeferredCallBytes = 40 (gl/frames/src/gl_frame_driver.cpp). The C++ HabufferCarry of L64 is 40 bytes
// too (p 8, a 4, pad 4, r 8, acc 4, iter 4, front 8), so a field added to or retyped in shared/ha_carry.glsl
// changes it.
static_assert(sizeof(HashKernel<std::uint64_t, false>::HabufferCarry) == 40,
              "HabufferCarry changed (shared/ha_carry.glsl): carry every field through HaDeferred, ha_defer and "
              "ha_carry_from in gl/glsl/shaders/ha_entry.glsl, update kDeferredCallBytes in gl/frames/src/gl_frame_driver.cpp to "
              "HaDeferred's std430 size, then this number to the new sizeof");

}  // namespace habuffer
