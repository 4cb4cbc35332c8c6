/// @file
/// Record layouts of SPEC 2: L64 = age | depth code | data, L32 = age | depth code.
#pragma once

#include <cstdint>
#include <string>

namespace habuffer {

/// Record layouts of SPEC 2, valued by their word's bits: L64 = age | depth code |
/// data, L32 = age | depth code.
enum class Layout : std::uint32_t { L64 = 64, L32 = 32 };

/// "L64" or "L32".
std::string to_string(Layout layout);

/// A runtime description of a record layout, with pack/unpack on 64-bit
/// integers for both layouts (an L32 record fits in the low 32 bits). The
/// arithmetic is the shared code of core/include/habuffer/shared/ha_record.glsl.
class RecordLayout {
 public:
  /// Throws std::invalid_argument unless 4 <= age_bits <= 12.
  RecordLayout(Layout layout, std::uint32_t age_bits);

  /// L64 or L32.
  [[nodiscard]] Layout layout() const { return layout_; }
  /// A, the age bits.
  [[nodiscard]] std::uint32_t age_bits() const { return age_bits_; }
  /// D = 32 - A, the depth code's bits.
  [[nodiscard]] std::uint32_t depth_bits() const { return 32 - age_bits_; }
  /// The record word's bits: 64 or 32.
  [[nodiscard]] std::uint32_t word_bits() const { return static_cast<std::uint32_t>(layout_); }
  /// The record word's bytes: 8 or 4.
  [[nodiscard]] std::uint32_t word_bytes() const { return word_bits() / 8; }
  /// Whether records hold a data word (L64).
  [[nodiscard]] bool has_data() const { return layout_ == Layout::L64; }
  /// AMAX = 2^A - 1.
  [[nodiscard]] std::uint32_t max_age() const { return (1u << age_bits_) - 1; }
  /// The largest depth code, 2^D - 1.
  [[nodiscard]] std::uint32_t max_code() const { return static_cast<std::uint32_t>((1ull << depth_bits()) - 1); }

  /// The record (age, code, data); L32 drops `data`.
  [[nodiscard]] std::uint64_t pack(std::uint32_t age, std::uint32_t code, std::uint32_t data) const;
  /// The record's age.
  [[nodiscard]] std::uint32_t age(std::uint64_t record) const;
  /// The record's depth code.
  [[nodiscard]] std::uint32_t code(std::uint64_t record) const;
  /// The record's data word (0 for L32).
  [[nodiscard]] std::uint32_t data(std::uint64_t record) const;
  /// `record` with its age replaced by `age`.
  [[nodiscard]] std::uint64_t with_age(std::uint64_t record, std::uint32_t age) const;

  /// SPEC 2: NaN and t outside [0, 1] (as float32) are invalid, never clamped.
  [[nodiscard]] static bool depth_valid(float t);
  /// code(t) of SPEC 2 for a valid depth t (larger is nearer).
  [[nodiscard]] std::uint32_t depth_code(float t) const;

  /// Same layout and age bits.
  friend bool operator==(const RecordLayout&, const RecordLayout&) = default;

 private:
  Layout layout_;
  std::uint32_t age_bits_;
};

}  // namespace habuffer
