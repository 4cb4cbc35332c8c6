/// @file
/// The CLI's technique flags: the options that pick a technique (--technique
/// NAME and the rows of the library's option table,
/// habuffer/technique_options.h), shared by render and build-lists, and the
/// refusal of options that the chosen technique would ignore.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "cli_args.h"
#include "habuffer/technique.h"

namespace habuffer::cli {

/// The technique options as parsed: the technique's fields of a
/// TechniqueConfig (technique, pool_capacity with 0 for --pool auto, layers,
/// occupancy, occupancy_words, depth_range); the buffer's fields are the
/// hash options' (hash_options.h). No field is declared twice.
using TechniqueOptions = TechniqueConfig;

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

/// The option table's row of CLI option `flag` as a command's declaration:
/// its value's shape, its default (TechniqueConfig's) and its help phrase
/// with the techniques that take it. std::logic_error for another name.
OptionSpec technique_option_spec(std::string_view flag);

/// Every row of the option table's `buffer_part` (see set_technique_options)
/// as declarations, in the table's order: a command that takes them all lists
/// none by name.
std::vector<OptionSpec> technique_option_specs(bool buffer_part);

/// The help's lines on --technique, written from the registry: every
/// technique's name and summary.
std::string technique_help();

}  // namespace habuffer::cli
