/// @file
/// Value rules that more than one front end reads: `habuffer render`'s
/// flags and the harness's technique words ("ha:cull=0.99:load=0.5") obey
/// the same rule, so that a value one refuses the other refuses too.
#pragma once

#include <cstdint>
#include <string_view>

#include "habuffer/extent.h"

namespace habuffer {

/// An early-cull threshold as the float32 both paths use: in (0, 1] and at
/// least the smallest normal float32 (a GPU may flush a subnormal to 0,
/// which turns cull off). Throws std::invalid_argument with the reason.
float parse_cull_threshold(std::string_view text);

/// A target load factor: a finite number in (0, 1]. Throws
/// std::invalid_argument with the reason.
double parse_load_factor(std::string_view text);

/// The table of `x` by `y` slots, sides computed in double precision for
/// `fragments` at `load` (both only for the message). Throws
/// std::invalid_argument naming the load when a side exceeds 2^31 or the
/// table 2^32 - 1 slots. The check comes before any cast: casting a huge or
/// infinite double (a tiny load) to an integer is undefined.
Extent table_of_sides(double x, double y, double load, std::uint64_t fragments);

/// The table that holds `fragments` at `load` on `screen`: the screen's
/// aspect, sides rounded up, at least the screen (SPEC 1); table_of_sides'
/// errors. Throws std::invalid_argument for a load that is not positive.
Extent table_for_load(Extent screen, std::uint64_t fragments, double load);

}  // namespace habuffer
