/// @file
/// The options every command that builds an HA-buffer shares (--screen,
/// --table, --layout, --age-bits, --offsets, --seed, --block, --threads,
/// --early-cull, --iter-limit, --lossless, --max-attempts), turned into the
/// library's configuration, so every such command reads them by the same rules.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "cli_args.h"
#include "habuffer/file_roles.h"
#include "habuffer/lossless_build.h"
#include "technique_flags.h"

namespace habuffer::cli {

/// The shared build options as parsed.
struct HashOptions {
  BufferConfig config;   ///< screen, table, layout, age bits, block, iteration limit, early cull
  OffsetSource offsets;  ///< --offsets and --seed
  std::string offsets_name;  ///< random, farthest or the file path
  InsertOptions insert;  ///< --threads and the CPU insertion's options
  ResizePolicy policy;   ///< how lossless mode grows the table
  std::uint32_t max_attempts = 1;  ///< > 1 in lossless mode
  bool lossless = false;  ///< --lossless
  bool gl = false;  ///< --path gl
  bool vk = false;  ///< --path vk (where the command offers it)
  TechniqueOptions technique;  ///< ha unless the command takes --technique
};

/// The technique's configuration: the technique's options over the buffer's;
/// --pool auto stays 0, the library's automatic pool (build_technique and the
/// GL containers size it from the fragments and grow it at once on a drop).
TechniqueConfig technique_config(const HashOptions& options);

/// The declarations of options several commands take, each declared once
/// (its value, default and help), picked by name: the build options above,
/// --technique and the technique option table's rows (habuffer/technique_options.h),
/// --threads, --insert-order. A command whose default differs (--path,
/// --table, --screen, --size) declares its own, saying why in its help.
/// std::logic_error for a name not shared.
std::vector<OptionSpec> shared_options(std::initializer_list<std::string_view> names);

/// Throws UsageError for bad values or conflicting sizes, DataError for a bad
/// offsets file. `screen` is required. With `techniques`, --technique,
/// --layers and --pool are parsed too (the command accepts them), and each
/// option only some techniques take refused with the others.
HashOptions parse_hash_options(const Args& args, bool techniques = false);

/// The parts other commands share: --layout, --age-bits, --block,
/// --iter-limit, --early-cull for a screen and table (zero table: auto);
/// --offsets and --seed.
BufferConfig parse_buffer_config(const Args& args, Extent screen, Extent table);
/// Throws UsageError naming --samples when `config` has more than one
/// sample per pixel and `technique` stores no lists (the blended baselines).
void refuse_samples_without_lists(const BufferConfig& config, Technique technique);
/// --offsets (random, farthest or a file, read for `config`'s table and ages) and --seed.
OffsetSource parse_offset_source(const Args& args, const BufferConfig& config);

/// Adds --offsets as an input when it names a file.


}  // namespace habuffer::cli
