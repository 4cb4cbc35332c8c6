/// @file
/// The hash table's slots: one zero-initialized, page-aligned anonymous
/// mapping. Up to 4 GiB it is committed at once; beyond, pages are committed
/// on first touch, so a table of more than 2^32 slots can exist (and be
/// indexed) while only the touched pages cost memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace habuffer {

/// A table of Word slots (std::uint64_t or std::uint32_t) in one anonymous
/// mapping (see above); move-only.
template <class Word>
class SlotStorage {
 public:
  /// No slots.
  SlotStorage() = default;
  /// `slots` zeroed slots. Throws std::length_error when they would exceed 2^48
  /// bytes, std::runtime_error when the mapping fails.
  explicit SlotStorage(std::uint64_t slots);
  /// Unmaps the slots.
  ~SlotStorage();
  SlotStorage(SlotStorage&& o) noexcept;
  SlotStorage& operator=(SlotStorage&& o) noexcept;
  SlotStorage(const SlotStorage&) = delete;
  SlotStorage& operator=(const SlotStorage&) = delete;

  /// The slots (nullptr when there are none).
  [[nodiscard]] Word* data() { return data_; }
  /// The slots (nullptr when there are none).
  [[nodiscard]] const Word* data() const { return data_; }
  /// The number of slots.
  [[nodiscard]] std::uint64_t size() const { return slots_; }
  /// Bytes of the slots.
  [[nodiscard]] std::uint64_t bytes() const { return slots_ * sizeof(Word); }
  /// The slots, read-only.
  [[nodiscard]] std::span<const Word> slots() const { return {data_, static_cast<std::size_t>(slots_)}; }

  /// Zeroes every slot; returns how many were non-empty (the CPU counterpart
  /// of the GL clear pass under an occlusion query).
  std::uint64_t clear_and_count();
  /// The number of non-zero slots.
  [[nodiscard]] std::uint64_t count_nonempty() const;
  /// Zeroes every slot.
  void clear();

 private:
  void release();
  Word* data_ = nullptr;
  std::uint64_t slots_ = 0;
  std::size_t mapped_ = 0;
};

extern template class SlotStorage<std::uint64_t>;
extern template class SlotStorage<std::uint32_t>;

}  // namespace habuffer
