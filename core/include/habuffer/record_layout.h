/// @file
/// Record layouts of SPEC 2: L64 = age | depth code | data, L32 = age | depth code.
#pragma once

#include <cstdint>
#include <string>

namespace habuffer {

enum class Layout : std::uint32_t { L64 = 64, L32 = 32 };

std::string to_string(Layout layout);

/// A runtime description of a record layout, with pack/unpack on 64-bit
/// integers for both layouts (an L32 record fits in the low 32 bits). The
/// arithmetic is the shared code of core/include/habuffer/shared/ha_record.glsl.
class RecordLayout {
 public:
  /// Throws std::invalid_argument unless 4 <= age_bits <= 12.
  RecordLayout(Layout layout, std::uint32_t age_bits);

  [[nodiscard]] Layout layout() const { return layout_; }
  [[nodiscard]] std::uint32_t age_bits() const { return age_bits_; }
  [[nodiscard]] std::uint32_t depth_bits() const { return 32 - age_bits_; }
  [[nodiscard]] std::uint32_t word_bits() const { return static_cast<std::uint32_t>(layout_); }
  [[nodiscard]] std::uint32_t word_bytes() const { return word_bits() / 8; }
  [[nodiscard]] bool has_data() const { return layout_ == Layout::L64; }
  [[nodiscard]] std::uint32_t max_age() const { return (1u << age_bits_) - 1; }
  [[nodiscard]] std::uint32_t max_code() const { return static_cast<std::uint32_t>((1ull << depth_bits()) - 1); }

  [[nodiscard]] std::uint64_t pack(std::uint32_t age, std::uint32_t code, std::uint32_t data) const;
  [[nodiscard]] std::uint32_t age(std::uint64_t record) const;
  [[nodiscard]] std::uint32_t code(std::uint64_t record) const;
  [[nodiscard]] std::uint32_t data(std::uint64_t record) const;
  [[nodiscard]] std::uint64_t with_age(std::uint64_t record, std::uint32_t age) const;

  /// SPEC 2: NaN and t outside [0, 1] (as float32) are invalid, never clamped.
  [[nodiscard]] static bool depth_valid(float t);
  [[nodiscard]] std::uint32_t depth_code(float t) const;

  friend bool operator==(const RecordLayout&, const RecordLayout&) = default;

 private:
  Layout layout_;
  std::uint32_t age_bits_;
};

}  // namespace habuffer
