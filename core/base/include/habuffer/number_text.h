/// @file
/// Numbers from text, read one way everywhere: command-line options, the
/// harness's scene and technique words, scene options. A value is read as
/// the type it becomes (a float32 option as float32, rounded once), and
/// text that cannot be that value exactly in kind is refused instead of
/// becoming another: trailing characters, a sign on an unsigned value, a
/// value beyond the type's range, a non-zero value that rounds to 0 or to
/// infinity, NaN.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace habuffer {

/// A decimal integer in [min, max]. Throws std::invalid_argument whose
/// message is the reason alone ("'x' is not an integer in 1..1048576"), for
/// the caller to prefix with the option or key.
std::uint64_t parse_unsigned(std::string_view text, std::uint64_t min = 0, std::uint64_t max = UINT64_MAX);

/// A finite decimal rounded once to float32 (text beyond float32's range,
/// or non-zero text that rounds to zero, is refused). Throws
/// std::invalid_argument with the reason.
float parse_float32(std::string_view text);

/// As parse_float32, for double.
double parse_float64(std::string_view text);

/// The shortest decimal that reads back as `v` ("1.1754944e-38").
std::string shortest_text(float v);
std::string shortest_text(double v);

}  // namespace habuffer
