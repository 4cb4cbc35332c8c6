/// @file
/// Constants of the spatial hash (spatial_hash.h), shared verbatim by C++ and
/// GLSL: preprocessor definitions only.
#ifndef HABUFFER_SH_CONSTANTS_H
#define HABUFFER_SH_CONSTANTS_H

// Outcome of one insert call: exactly one per call (the spatial hash's
// counters). A call places its key and moves the records it evicts on, so:
// STORED: a key new to the table is in it, and every record moved is too.
// REVIVED: the key replaced its own tombstone (an erased key's marker).
// STORED_TOMBSTONE_DROPPED: the key is in; the record pushed out at the end
// was a tombstone, which holds no key (nothing is lost).
// DUPLICATE: the key was there or met another record of itself; the rule
// kept one of the two (the table holds the key once).
// FAILED_AGE, FAILED_ITER: the record carried at the end (the key's own or
// one it evicted) is not in the table; the container grows and inserts it
// again (lossless) or counts it lost.
#define HABUFFER_SH_STORED 0u
#define HABUFFER_SH_REVIVED 1u
#define HABUFFER_SH_STORED_TOMBSTONE_DROPPED 2u
#define HABUFFER_SH_DUPLICATE 3u
#define HABUFFER_SH_FAILED_AGE 4u
#define HABUFFER_SH_FAILED_ITER 5u
#define HABUFFER_SH_OUTCOME_COUNT 6u
// Not outcomes: the call goes on (HABUFFER_SH_PENDING), or was cut short by
// something other than the table (HABUFFER_SH_CUT, GPU path only: an emulated atomic
// gave up on a busy lock, or the driver's loop budget ended the loop) and
// its carry must be resumed.
#define HABUFFER_SH_PENDING 6u
#define HABUFFER_SH_CUT 7u

#define HABUFFER_SH_DEFAULT_AGE_BITS 8u
#define HABUFFER_SH_MIN_AGE_BITS 4u
#define HABUFFER_SH_MAX_AGE_BITS 12u
#define HABUFFER_SH_DEFAULT_ITER_LIMIT 65536u

// The miss filter (sh_spatial.glsl, issue 36): one block of
// HABUFFER_SH_FILTER_WORDS 32-bit words (one 64-byte line) per
// 2^HABUFFER_SH_FILTER_SHIFT_X positions along x and 512 / (bits a position
// x 2^HABUFFER_SH_FILTER_SHIFT_X) along y; 16 bits a position by default.
#define HABUFFER_SH_FILTER_SHIFT_X 3u
#define HABUFFER_SH_FILTER_WORDS 16u
#define HABUFFER_SH_DEFAULT_FILTER_BITS 16u

#endif
