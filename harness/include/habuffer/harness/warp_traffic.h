/// @file
/// The memory traffic of warps (issue 36, part 7): what a GPU's memory system
/// sees when 32 lanes run one code path together. A host replays each lane of
/// a warp in turn, recording every access the lane's code makes (an address,
/// whether it loads, stores or runs an atomic, and whether the lane waits for
/// its value), then ends the warp; the recorder steps the lanes' i-th accesses
/// together as one warp instruction per static access site (lanes that have
/// finished, or whose i-th access is at another site, idle) and counts:
///
/// - sectors and lines: the distinct 32-byte sectors and 128-byte lines the
///   instruction touches (a coalesced load of 32 consecutive 4-byte words is
///   4 sectors, 1 line; 32 scattered words are 32 of each);
/// - atomics: lane atomics (read-modify-writes, whether or not the lane uses
///   the old value) and their conflicts: lane atomics of the instruction
///   beyond the first on each address (32 lanes on one word: 31), which the
///   memory system serializes;
/// - chain: the dependent-load chain of the warp, the most accesses any of its
///   lanes waited for in sequence. Every access whose value the code uses
///   (a load of a buffer the pass writes, an atomic whose old value it reads)
///   is a link: in these kernels the next address or whether to go on
///   depends on it (probe loops, list walks). Stores, atomics whose result is
///   unused (reductions) and loads of read-only buffers (the probe offsets,
///   L1-resident) are not links. `chain` sums the warps' chains, so
///   chain / warps is the mean number of memory round trips a warp waits for.
///
/// Accesses are naturally aligned and at most 16 bytes: each lies in one sector.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace habuffer::harness {

/// What an access does (see the file comment).
enum class AccessKind : std::uint8_t {
  Load,       ///< a plain read
  Store,      ///< a plain write
  Atomic,     ///< a read-modify-write whose old value the lane uses
  Reduction,  ///< a read-modify-write whose result is unused (fire and forget)
};

/// One pass's counts, summed over its warps (see the file comment).
struct TrafficCounts {
  std::uint64_t warps = 0;         ///< warps replayed
  std::uint64_t lanes = 0;         ///< lanes that ran (fragments or pixels)
  std::uint64_t instructions = 0;  ///< warp memory instructions issued
  std::uint64_t accesses = 0;      ///< lane accesses
  std::uint64_t sectors = 0;       ///< distinct 32-byte sectors per instruction, summed
  std::uint64_t lines = 0;         ///< distinct 128-byte lines per instruction, summed
  std::uint64_t atomics = 0;       ///< lane atomics and reductions
  std::uint64_t conflicts = 0;     ///< lane atomics beyond the first on an address in one instruction
  std::uint64_t chain = 0;         ///< the warps' dependent-load chains, summed
  std::uint32_t chain_max = 0;     ///< the longest chain of any warp
  /// Adds `o`'s counts (chain_max: the larger).
  TrafficCounts& operator+=(const TrafficCounts& o);
};

/// Records the accesses of one warp's lanes and folds each ended warp into
/// counts() (see the file comment).
class WarpRecorder {
 public:
  /// Lanes of a warp.
  static constexpr std::uint32_t kLanes = 32;

  /// The accesses recorded next are lane `lane`'s (below kLanes) of the current warp.
  void begin_lane(std::uint32_t lane);
  /// One access of the current lane at byte `address`. `site` names the
  /// static access in the code (accesses at different sites never share an
  /// instruction); `waits`: the lane uses the value before going on (a chain link).
  void record(std::uint16_t site, std::uint64_t address, AccessKind kind, bool waits);
  /// Ends the current warp (lanes without accesses count as having run if
  /// begin_lane named them) and adds it to counts().
  void end_warp();
  /// The counts of the warps ended so far.
  [[nodiscard]] const TrafficCounts& counts() const { return counts_; }

 private:
  struct Access {
    std::uint64_t address;
    std::uint16_t site;
    AccessKind kind;
  };
  std::array<std::vector<Access>, kLanes> lanes_;
  std::array<std::uint32_t, kLanes> chain_{};
  std::uint32_t lane_ = 0;
  std::uint32_t lanes_begun_ = 0;  // bit per lane named by begin_lane
  TrafficCounts counts_;
};

}  // namespace habuffer::harness
