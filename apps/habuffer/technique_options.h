/// @file
/// The options that pick a technique (--technique NAME and the option table's
/// rows, habuffer/technique_options.h), shared by render and build-lists, and
/// the refusal of options that the chosen technique would ignore.
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

/// Parses --technique and the technique's options of the option table
/// (habuffer/technique_options.h: --layers, --pool, --occupancy,
/// --occupancy-words, --depth-range), and refuses every option that only some
/// techniques take (their descriptors' option lists) where the chosen
/// technique does not take it.
TechniqueOptions parse_technique_options(const Args& args);

/// Every option of the option table given on the command line, of the
/// BufferConfig part (`buffer_part`: --early-cull, --saturation, --age-bits,
/// --block, --iter-limit) or the TechniqueChoice part, set in `config`
/// ("option --NAME: REASON" for a bad value); then refuses an option given
/// without the option it needs (--occupancy-words without --occupancy on).
void set_technique_options(const Args& args, TechniqueConfig& config, bool buffer_part);

/// One help line per option of the table's `buffer_part` (see
/// set_technique_options): usage, what it sets, its default (TechniqueConfig's
/// own) and the techniques that take it.
std::string technique_option_help(bool buffer_part);

/// The help's lines on --technique, written from the registry: every
/// technique's name and summary, and the technique's own options (the table's).
std::string technique_help();

}  // namespace habuffer::cli
