/// @file
/// Changes to a running technique's configuration, by the technique option
/// table's rows (habuffer/technique_options.h): the panel and the scripted
/// switches edit configurations only through these, so every rule the CLI
/// applies to an option applies here too.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "habuffer/technique.h"
#include "habuffer/technique_options.h"

namespace habuffer::view {

/// `config` as technique `t`: the options `t` does not take back at their
/// defaults (early cull, K, the pool, ...), the screen, layout and the rest kept.
TechniqueConfig with_technique(const TechniqueConfig& config, Technique t);
/// The option rows the panel shows for `t`: those every technique takes and
/// those its descriptor takes (never the technique-word knobs alone).
std::vector<const TechniqueOption*> editable_options(Technique t);
/// `config` with option `o` set from `text` (the CLI's spelling); throws
/// std::invalid_argument naming the option and the reason for a value the
/// option refuses. The configuration's rules are checked where the driver
/// is made (OitSession::reconfigure shows that refusal).
TechniqueConfig with_option(const TechniqueConfig& config, const TechniqueOption& o, const std::string& text);
/// The option's value in `config` as the CLI writes it.
std::string option_text(const TechniqueOption& o, const TechniqueConfig& config);

}  // namespace habuffer::view
