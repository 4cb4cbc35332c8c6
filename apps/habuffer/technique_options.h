/// @file
/// The options that pick a technique (--technique NAME, --layers K, --pool N,
/// --occupancy on|off, --occupancy-words D, --depth-range NEAR,FAR), shared
/// by render and build-lists, and the refusal of options that the chosen
/// technique would ignore.
#pragma once

#include <cstdint>

#include "cli_args.h"
#include "habuffer/technique.h"

namespace habuffer::cli {

/// The technique options as parsed: the technique's fields of a
/// TechniqueConfig (technique, pool_capacity with 0 for --pool auto, layers,
/// occupancy, occupancy_words, depth_range); the buffer's fields are the
/// hash options' (hash_options.h). No field is declared twice.
using TechniqueOptions = TechniqueConfig;

/// Names to add to a command's accepted options.
inline constexpr const char* kTechniqueValued[] = {"technique",       "layers",      "pool", "occupancy",
                                                   "occupancy-words", "depth-range", "saturation"};

/// Parses --technique, --layers (arrays, kbuffer), --pool (lists,
/// sorted-lists; "auto" or a node count), --occupancy and --occupancy-words
/// (kbuffer), --depth-range (kbuffer, wboit), and refuses every option that
/// only some techniques take (their descriptors' option lists) where the
/// chosen technique does not take it.
TechniqueOptions parse_technique_options(const Args& args);

/// The help's lines on --technique, written from the registry: every
/// technique's name and summary, and where its own options are listed.
std::string technique_help();

}  // namespace habuffer::cli
