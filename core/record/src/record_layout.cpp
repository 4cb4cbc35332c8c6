#include "habuffer/record_layout.h"

#include <stdexcept>

#include "habuffer/glsl_env.h"

namespace habuffer {
namespace {

// The record functions of the shared GLSL, for one word size.
template <class Word>
struct RecordCodec {
  HABUFFER_GLSL_CLASS_PRELUDE
  using ha_word = Word;
  uint habuffer_age_bits;
  uint habuffer_coverage_bits;
  static constexpr uint ha_word_bits = sizeof(Word) * 8;
  static constexpr uint ha_payload_bits = sizeof(Word) == 8 ? 32u : 0u;
  RecordCodec(uint age_bits, uint coverage_bits) : habuffer_age_bits(age_bits), habuffer_coverage_bits(coverage_bits) {}
#include "habuffer/shared/ha_record.glsl"
};

template <class F>
auto with_codec(Layout layout, std::uint32_t age_bits, std::uint32_t coverage_bits, F&& f) {
  if (layout == Layout::L64) return f(RecordCodec<std::uint64_t>(age_bits, coverage_bits));
  return f(RecordCodec<std::uint32_t>(age_bits, coverage_bits));
}

}  // namespace

std::string to_string(Layout layout) { return layout == Layout::L64 ? "L64" : "L32"; }

bool RecordLayout::samples_valid(std::uint32_t samples) {
  return samples == 1 || samples == 2 || samples == 4 || samples == kMaxSamples;
}

RecordLayout::RecordLayout(Layout layout, std::uint32_t age_bits, std::uint32_t samples)
    : layout_(layout), age_bits_(age_bits), samples_(samples) {
  if (layout != Layout::L64 && layout != Layout::L32)
    throw std::invalid_argument("record layout must be 64 or 32 bits");
  if (age_bits < HABUFFER_MIN_AGE_BITS || age_bits > HABUFFER_MAX_AGE_BITS)
    throw std::invalid_argument("age bits " + std::to_string(age_bits) + " outside " +
                                std::to_string(HABUFFER_MIN_AGE_BITS) + ".." + std::to_string(HABUFFER_MAX_AGE_BITS));
  if (!samples_valid(samples))
    throw std::invalid_argument("samples " + std::to_string(samples) + " is not 1, 2, 4 or 8");
}

std::uint64_t RecordLayout::pack(std::uint32_t age, std::uint32_t code, std::uint32_t data) const {
  return with_codec(layout_, age_bits_, coverage_bits(), [&](auto c) { return std::uint64_t{c.ha_pack(age, code, data)}; });
}
std::uint32_t RecordLayout::age(std::uint64_t r) const {
  return with_codec(layout_, age_bits_, coverage_bits(), [&](auto c) { return c.ha_age(static_cast<typename decltype(c)::ha_word>(r)); });
}
std::uint32_t RecordLayout::code(std::uint64_t r) const {
  return with_codec(layout_, age_bits_, coverage_bits(), [&](auto c) { return c.ha_code(static_cast<typename decltype(c)::ha_word>(r)); });
}
std::uint32_t RecordLayout::data(std::uint64_t r) const {
  return with_codec(layout_, age_bits_, coverage_bits(), [&](auto c) { return c.ha_data(static_cast<typename decltype(c)::ha_word>(r)); });
}
std::uint64_t RecordLayout::with_age(std::uint64_t r, std::uint32_t age) const {
  return with_codec(layout_, age_bits_, coverage_bits(), [&](auto c) {
    return std::uint64_t{c.ha_with_age(static_cast<typename decltype(c)::ha_word>(r), age)};
  });
}
bool RecordLayout::depth_valid(float t) { return RecordCodec<std::uint64_t>(HABUFFER_DEFAULT_AGE_BITS, 0).ha_depth_valid(t); }
std::uint32_t RecordLayout::depth_code(float t) const {
  return RecordCodec<std::uint64_t>(age_bits_, coverage_bits()).ha_depth_code(t);
}
bool RecordLayout::covers_sample(std::uint32_t coverage) const {
  return RecordCodec<std::uint64_t>(age_bits_, coverage_bits()).ha_covers_sample(coverage);
}
bool RecordLayout::fragment_valid(float t, std::uint32_t coverage) const {
  return RecordCodec<std::uint64_t>(age_bits_, coverage_bits()).ha_fragment_valid(t, coverage);
}
std::uint32_t RecordLayout::fragment_code(float t, std::uint32_t coverage) const {
  return RecordCodec<std::uint64_t>(age_bits_, coverage_bits()).ha_fragment_code(t, coverage);
}

}  // namespace habuffer
