/// @file
/// Value rules that more than one front end reads: `habuffer render`'s
/// flags and the harness's technique words ("ha:cull=0.99:load=0.5") obey
/// the same rule, so that a value one refuses the other refuses too.
#pragma once

#include <string_view>

namespace habuffer {

/// An early-cull threshold as the float32 both paths use: in (0, 1] and at
/// least the smallest normal float32 (a GPU may flush a subnormal to 0,
/// which turns cull off). Throws std::invalid_argument with the reason.
float parse_cull_threshold(std::string_view text);

/// A target load factor: a finite number in (0, 1]. Throws
/// std::invalid_argument with the reason.
double parse_load_factor(std::string_view text);

}  // namespace habuffer
