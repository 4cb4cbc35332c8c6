/// @file
/// Record layouts of SPEC 2: L64 = age | depth code | data, L32 = age | depth
/// code; on a multisampled screen the code field ends in the coverage mask.
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
/// arithmetic is the shared code of core/{record,hash}/include/habuffer/shared/ha_record.glsl.
class RecordLayout {
 public:
  /// Throws std::invalid_argument unless 4 <= age_bits <= 12 and samples is
  /// 1, 2, 4 or 8 (kMaxSamples).
  RecordLayout(Layout layout, std::uint32_t age_bits, std::uint32_t samples = 1);

  /// The most samples per pixel a record's coverage mask holds.
  static constexpr std::uint32_t kMaxSamples = 8;
  /// Whether `samples` is 1, 2, 4 or 8.
  [[nodiscard]] static bool samples_valid(std::uint32_t samples);

  /// L64 or L32.
  [[nodiscard]] Layout layout() const { return layout_; }
  /// A, the age bits.
  [[nodiscard]] std::uint32_t age_bits() const { return age_bits_; }
  /// S, the samples per pixel (1: not multisampled).
  [[nodiscard]] std::uint32_t samples() const { return samples_; }
  /// C, the coverage mask's bits: S above one sample, else 0.
  [[nodiscard]] std::uint32_t coverage_bits() const { return samples_ > 1 ? samples_ : 0; }
  /// 32 - A, the code field's bits (the depth code, then the coverage mask).
  [[nodiscard]] std::uint32_t code_bits() const { return 32 - age_bits_; }
  /// D = 32 - A - C, the depth code's own bits.
  [[nodiscard]] std::uint32_t depth_bits() const { return code_bits() - coverage_bits(); }
  /// The record word's bits: 64 or 32.
  [[nodiscard]] std::uint32_t word_bits() const { return static_cast<std::uint32_t>(layout_); }
  /// The record word's bytes: 8 or 4.
  [[nodiscard]] std::uint32_t word_bytes() const { return word_bits() / 8; }
  /// Whether records hold a data word (L64).
  [[nodiscard]] bool has_data() const { return layout_ == Layout::L64; }
  /// AMAX = 2^A - 1.
  [[nodiscard]] std::uint32_t max_age() const { return (1u << age_bits_) - 1; }
  /// The code field's largest value, 2^(32 - A) - 1.
  [[nodiscard]] std::uint32_t max_code() const { return static_cast<std::uint32_t>((1ull << code_bits()) - 1); }
  /// The coverage bits of a code field, (1 << C) - 1.
  [[nodiscard]] std::uint32_t coverage_mask() const { return (1u << coverage_bits()) - 1u; }

  /// The record (age, code, data); L32 drops `data`.
  [[nodiscard]] std::uint64_t pack(std::uint32_t age, std::uint32_t code, std::uint32_t data) const;
  /// The record's age.
  [[nodiscard]] std::uint32_t age(std::uint64_t record) const;
  /// The record's code field: its depth code, with its coverage mask in the low C bits.
  [[nodiscard]] std::uint32_t code(std::uint64_t record) const;
  /// The record's coverage mask (0 when not multisampled).
  [[nodiscard]] std::uint32_t coverage(std::uint64_t record) const { return code(record) & coverage_mask(); }
  /// The record's data word (0 for L32).
  [[nodiscard]] std::uint32_t data(std::uint64_t record) const;
  /// `record` with its age replaced by `age`.
  [[nodiscard]] std::uint64_t with_age(std::uint64_t record, std::uint32_t age) const;

  /// SPEC 2: NaN and t outside [0, 1] (as float32) are invalid, never clamped.
  [[nodiscard]] static bool depth_valid(float t);
  /// code(t) of SPEC 2 for a valid depth t (larger is nearer), in the code
  /// field's high D bits (its coverage bits 0).
  [[nodiscard]] std::uint32_t depth_code(float t) const;
  /// Whether a fragment of this coverage word is stored: always when not
  /// multisampled, else when its mask names one of the S samples (otherwise it is invalid).
  [[nodiscard]] bool covers_sample(std::uint32_t coverage) const;
  /// Whether a fragment at depth t with coverage word `coverage` makes a
  /// record: depth_valid(t) and covers_sample(coverage); else it is invalid.
  [[nodiscard]] bool fragment_valid(float t, std::uint32_t coverage) const;
  /// The code field of a fragment at valid depth t with coverage word `coverage`.
  [[nodiscard]] std::uint32_t fragment_code(float t, std::uint32_t coverage) const;

  /// Same layout, age bits and samples.
  friend bool operator==(const RecordLayout&, const RecordLayout&) = default;

 private:
  Layout layout_;
  std::uint32_t age_bits_;
  std::uint32_t samples_;
};

}  // namespace habuffer
