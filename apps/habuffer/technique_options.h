// The options that pick a technique (--technique ha|lists|arrays, --layers K,
// --pool N), shared by render and build-lists, and the refusal of options
// that the chosen technique would ignore.
#pragma once

#include <cstdint>

#include "cli_args.h"
#include "habuffer/technique.h"

namespace habuffer::cli {

struct TechniqueOptions {
  Technique technique = Technique::Ha;
  std::uint32_t layers = HA_DEFAULT_LAYERS;  // arrays
  std::uint64_t pool = 0;                    // lists; 0: auto (as many as the fragments need)
};

// Names to add to a command's accepted options.
inline constexpr const char* kTechniqueValued[] = {"technique", "layers", "pool"};

// Parses --technique, --layers (arrays only) and --pool (lists only; "auto"
// or a node count), and refuses the HA-buffer's own options (--table,
// --block, --iter-limit, --early-cull, --offsets, --seed, and `more` given
// by the command) with another technique.
TechniqueOptions parse_technique_options(const Args& args, std::initializer_list<const char*> more = {});

}  // namespace habuffer::cli
