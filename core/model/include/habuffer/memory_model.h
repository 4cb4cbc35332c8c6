/// @file
/// The memory of each technique by formula (seed 000, Table 1), beside what
/// the containers allocate: the paper's formulas in the paper's units (56-bit
/// fragments: 24-bit depth and 32-bit RGBA, 32-bit pointers, one max-age byte
/// per 8x8 block), and the same formulas with our record sizes, which the CPU
/// containers match to the byte (a test checks it).
#pragma once

#include <cstdint>

#include "habuffer/fragment_buffer.h"
#include "habuffer/technique.h"

namespace habuffer {

/// The technique's storage, our sizes, for `capacity` records (slots, nodes,
/// or ignored for arrays, whose capacity is K per pixel):
///   HA-buffer:    slots * word + max-age cells * 4 + AMAX offsets * 8
///   linked lists: pixels * 4 (heads) + nodes * 12 (code, data, link) + 4 (counter)
///   fixed arrays: pixels * 4 (counters) + K * pixels * 8 (code, data) + 4 (overflow note)
/// The GPU path adds, for the HA-buffer, a 32-bit lock per 2^HABUFFER_LOCK_SHIFT
/// slots in atomic mode emulated64 and 8 bytes of query result; and for every technique the
/// frame's tallies, parameters, capture and deferred-call buffers.
std::uint64_t memory_model_bytes(const TechniqueConfig& config, std::uint64_t capacity);
/// The model of a container as it is (its configuration and capacity).
std::uint64_t memory_model_bytes(const FragmentBuffer& buffer);

/// Seed 000's Table 1 in bytes for `fragments` stored fragments on `pixels`
/// pixels: HA-buffer V/8 + 64F/L bits (L = load), linked lists 32V + 88F bits,
/// paged lists (pages of `page` fragments) at least 40V + F/K (56K + 32) bits;
/// fixed arrays (not in the table) 32V + 56KV bits; sorted lists as lists;
/// the k-buffer 56KV bits; wboit 160V bits (RGBA32F + R32F), blend 128V bits.
double paper_memory_bytes(Technique technique, std::uint64_t pixels, std::uint64_t fragments, double load,
                          std::uint32_t layers);
/// Seed 000's paged lists in bytes: 40V + F/K (56K + 32) bits, K = `page`
/// fragments per page.
double paper_paged_lists_bytes(std::uint64_t pixels, std::uint64_t fragments, std::uint32_t page);

}  // namespace habuffer
