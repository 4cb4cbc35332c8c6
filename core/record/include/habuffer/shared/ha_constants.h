/// @file
/// Constants shared verbatim by the C++ path and the GLSL path.
/// Only preprocessor definitions live here, so the file is valid C++ and GLSL.
#ifndef HABUFFER_CONSTANTS_H
#define HABUFFER_CONSTANTS_H

// Outcome of one insert call (SPEC 6, invariant 1): exactly one per call, for
// every technique. The drop reasons are the technique's own: the HA-buffer
// fails by age or iterations, linked lists by an exhausted node pool, fixed
// arrays by a full pixel (docs/spec-notes.md, "Techniques").
#define HABUFFER_STORED 0u
#define HABUFFER_DUPLICATE 1u
#define HABUFFER_CULLED 2u
#define HABUFFER_FAILED_AGE 3u
#define HABUFFER_FAILED_ITER 4u
#define HABUFFER_INVALID 5u
#define HABUFFER_DROPPED_POOL 6u
#define HABUFFER_DROPPED_LAYERS 7u
// Rejected before insertion: behind the pixel's saturation depth (a fragment
// culled earlier lay in front of it, so it is hidden as surely), or beyond
// the k-buffer's occupancy limit (at least k nearer fragments exist).
#define HABUFFER_SATURATED 8u
#define HABUFFER_OCCUPANCY_REJECTED 9u
// Blended into the image without being stored (weighted blended OIT, plain blending).
#define HABUFFER_BLENDED 10u
#define HABUFFER_OUTCOME_COUNT 11u
// Not outcomes: the insert call goes on (ha_insert_step), or it was cut short
// by something other than the table and its carried state must be resumed
// (GPU path only: an emulated atomic that gave up, the driver's loop budget).
// HABUFFER_UNCOUNTED: a call of a pass that inserts nothing (the k-buffer's
// occupancy fill pass), not an insert call.
#define HABUFFER_PENDING 11u
#define HABUFFER_CUT 12u
#define HABUFFER_UNCOUNTED 13u

// Fixed arrays: default layers per pixel (Crassin 2010 uses 16).
#define HABUFFER_DEFAULT_LAYERS 16u
// Most layers per pixel (fixed arrays, k-buffer) an option or word accepts.
#define HABUFFER_MAX_LAYERS 65536u
// The k-buffer's occupancy map: 32-bit words per pixel (32 buckets each)
// by default and at most (seed 003 uses d = 32 words for k up to 32).
#define HABUFFER_DEFAULT_OCCUPANCY_WORDS 4u
#define HABUFFER_MAX_OCCUPANCY_WORDS 32u
// The sort of lists and arrays: a pixel's entries up to this many are sorted
// in a private array by insertion sort (registers on a GPU); longer ones in
// place in the technique's buffer (merge sort of the linked list, heap sort
// of the array), as GP5's post-sort variants switch algorithms by length.
#define HABUFFER_SORT_LOCAL 32u

// Traversal step results (SPEC 7).
#define HABUFFER_VISIT_STOP 0u
#define HABUFFER_VISIT_SKIP 1u
#define HABUFFER_VISIT_EMIT 2u

// Record layouts (SPEC 2).
#define HABUFFER_LAYOUT_64 64u
#define HABUFFER_LAYOUT_32 32u
#define HABUFFER_MIN_AGE_BITS 4u
#define HABUFFER_MAX_AGE_BITS 12u
// The most samples per pixel of a multisampled screen (a record's coverage mask).
#define HABUFFER_MAX_SAMPLES 8u
#define HABUFFER_DEFAULT_AGE_BITS 8u

// Defaults of SPEC 5, 6 and 8.
#define HABUFFER_DEFAULT_BLOCK 8u
#define HABUFFER_DEFAULT_ITER_LIMIT 65536u
// The largest iteration limit: no insert call may probe longer than this
// (about 2^28 probes) on either path.
#define HABUFFER_MAX_ITER_LIMIT 268431359u

// GPU path: the outcome tallies are striped: HABUFFER_COUNTER_STRIPES copies of
// the counters, one cache line (HABUFFER_COUNTER_STRIDE words) each, a call adding
// to the stripe of its pixel (ha_counter_stripe) and the host summing them,
// so the fragments of a frame do not all hit the same few addresses (exact:
// every call still adds once).
#define HABUFFER_COUNTER_STRIDE 16u
#define HABUFFER_COUNTER_STRIPES 64u
// GPU counters after the outcomes in each stripe: the slot writes, when asked
// for (atomicMax calls that raised a slot, including records later evicted:
// the work an insertion order costs); the records the sort pass of lists and
// arrays merged as duplicates (counted stored at insertion, moved to
// duplicates by the host); the pixels the sort pass finished (every pixel of
// the screen must: a driver that ends an invocation early leaves the count
// short, never silently); the calls whose pixel lay outside the screen
// (counted invalid too; a loss: a host drawing beyond the screen it
// configured, e.g. after a window resize); the calls of a counting gather
// (habuffer_gather_phase HABUFFER_PHASE_COUNT: on-screen calls, nothing
// inserted), which size an automatic container before its first frame.
#define HABUFFER_COUNTER_SLOT_WRITES 11u
#define HABUFFER_COUNTER_MERGED 12u
#define HABUFFER_COUNTER_SORT_DONE 13u
#define HABUFFER_COUNTER_OFF_SCREEN 14u
#define HABUFFER_COUNTER_COUNTED 15u
#define HABUFFER_GPU_COUNTER_COUNT 16u
// The parameter habuffer_gather_phase: an inserting gather, the k-buffer's
// occupancy fill (inserts nothing), the frame driver's counting gather
// (counts the calls, inserts nothing).
#define HABUFFER_PHASE_INSERT 0u
#define HABUFFER_PHASE_FILL 1u
#define HABUFFER_PHASE_COUNT 2u
// Words after the stripes, on a cache line of their own, that are not sums:
// the linked lists' node counter (one atomic add per fragment, the
// technique's own hot spot) and the most fragments a fixed-array pixel
// received when some pixel overflowed.
#define HABUFFER_COUNTER_NODES (HABUFFER_COUNTER_STRIPES * HABUFFER_COUNTER_STRIDE)
#define HABUFFER_COUNTER_MOST_ARRIVED (HABUFFER_COUNTER_NODES + 1u)
// Insert calls from a shader built from another frame driver's module
// (its HABUFFER_MODULE_ID is not the parameter habuffer_module_id): nothing
// inserted; the driver refuses the frame naming the count.
#define HABUFFER_COUNTER_FOREIGN (HABUFFER_COUNTER_NODES + 3u)  // + 2 is the paged lists' wasted pages
// Insert calls that took their coverage from a rasterizer of another sample
// count than the buffer's (gl_NumSamples against BufferConfig::samples), and
// the most samples seen: nothing inserted; the driver refuses the frame.
#define HABUFFER_COUNTER_SAMPLES_MISMATCH (HABUFFER_COUNTER_NODES + 4u)
#define HABUFFER_COUNTER_SAMPLES_SEEN (HABUFFER_COUNTER_NODES + 5u)
// Insert calls that entered a technique's insert in an inserting gather,
// counted before the call can be cut short: only where the module defines
// HABUFFER_COUNT_CALLS (the frame driver does on an implementation whose loop
// budget can end a call without an outcome: llvmpipe), so the driver counts
// such calls failed_iter without asking its host for a call count.
#define HABUFFER_COUNTER_CALLS (HABUFFER_COUNTER_NODES + 6u)
// Set when an insert call of a gather with habuffer_stop_at_failure failed
// (lossless mode's attempt that will be gathered again into the table sized
// for its count): the calls after it are counted in the striped
// HABUFFER_COUNTER_COUNTED (unused outside a counting gather) and not
// inserted, so a jump's failed gather costs about a counting gather, not a
// gather into an overfull table; the driver counts them failed_iter of that
// attempt (FrameReport::skipped).
#define HABUFFER_COUNTER_FAILED_ONCE (HABUFFER_COUNTER_NODES + 7u)
#define HABUFFER_COUNTER_WORDS (HABUFFER_COUNTER_NODES + HABUFFER_COUNTER_STRIDE)
// The GPU path's append buffers (capture, deferred calls) start with this
// many words: the append count, then padding to 16 bytes.
#define HABUFFER_APPEND_HEADER_WORDS 4u
// An emulated 64-bit atomic tries a contended slot lock this many times in a
// row before the insert call is cut short and deferred to the frame's resume
// pass (2^24 attempts, a fraction of a second: long enough to outlast a lock
// holder the OS preempted, where the driver lets a loop run that long).
#define HABUFFER_DEFAULT_LOCK_SPIN_LIMIT 16777216u

// Emulated64: one lock word guards 2^HABUFFER_LOCK_SHIFT neighbouring slots (each
// critical section takes one lock and releases it in the same call, so
// sharing cannot deadlock): 0.5 byte a slot instead of 4, which keeps the
// GPU HA-buffer below linked lists' memory at load 0.8.
#define HABUFFER_LOCK_SHIFT 3u

// IEEE-754 binary32 bit patterns used by the depth-validity test: a float is
// in [0, 1] exactly when its bits are in [0, 0x3F800000] or it is -0.
#define HABUFFER_FLOAT_ONE_BITS 0x3F800000u
#define HABUFFER_FLOAT_NEG_ZERO_BITS 0x80000000u

#endif
