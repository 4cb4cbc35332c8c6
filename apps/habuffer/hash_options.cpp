#include "hash_options.h"

#include <algorithm>
#include <limits>

#include "habuffer/interchange.h"
#include "habuffer/memory_budget.h"
#include "habuffer/option_rules.h"
#include "habuffer/technique_descriptor.h"
#include "file_values.h"

namespace habuffer::cli {

namespace {

// The shared declarations (see shared_options), besides the technique table's rows.
const std::vector<OptionSpec>& shared_declarations() {
  static const std::vector<OptionSpec> specs{
      {"technique", "NAME", "ha", "the technique (listed below)"},
      {"layout", "64|32", "64", "record layout: 64 bits (depth and colour) or 32 (depth only)"},
      {"offsets", "random|farthest|OFFSETS.csv", "random", "the HA-buffer's probe offsets", reads_in(offsets_file, "{}")},
      {"seed", "N", "1", "the offsets' seed"},
      {"threads", "N", "0",
       "CPU insertion threads: 0 uses every hardware thread, at most one per 32768 fragments"},
      {"insert-mode", "auto|serial|atomic|owner", "auto",
       "how CPU threads insert (serial: one thread, the default --threads then 1); every mode builds the same "
       "table"},
      {"insert-order", "auto|arrival|pixel", "auto", "the HA-buffer's insertion order on the CPU (habuffer info)"},
      {"lossless", "", "", "grow the technique's buffers and rebuild until nothing is dropped"},
      {"max-attempts", "N", "16", "lossless mode's builds at most"},
  };
  return specs;
}

}  // namespace

std::vector<OptionSpec> shared_options(std::initializer_list<std::string_view> names) {
  std::vector<OptionSpec> out;
  for (std::string_view name : names) {
    const auto& shared = shared_declarations();
    const auto it = std::find_if(shared.begin(), shared.end(), [&](const OptionSpec& o) { return o.name == name; });
    out.push_back(it != shared.end() ? *it : technique_option_spec(name));
  }
  return out;
}

BufferConfig parse_buffer_config(const Args& args, Extent screen, Extent table) {
  BufferConfig c;
  c.screen = screen;
  c.table = table;
  const std::string layout = args.str("layout");
  if (layout != "64" && layout != "32") throw UsageError("option --layout: '" + layout + "' is not 64 or 32");
  c.layout = layout == "64" ? Layout::L64 : Layout::L32;
  // The technique option table's BufferConfig part: --early-cull (the
  // threshold is a float32 on both paths; below the smallest normal float32
  // a GPU may flush it to 0, which turns cull off), --saturation, --age-bits,
  // --block, --iter-limit.
  TechniqueConfig t;
  t.buffer = c;
  set_technique_options(args, t, true);
  c = t.buffer;
  usage_errors("", [&] {
    c.validate();
    // The least any technique allocates: per-pixel images and counts (32
    // bytes a pixel over the buffers and frames) and the table's records.
    check_fits_in_memory("screen " + c.screen.str() + " (table " + c.table_or_screen().str() + ")",
                         saturating_product(c.screen.area(), 32) +
                             saturating_product(c.table_or_screen().area(), c.record_layout().word_bytes()));
  });
  return c;
}

void refuse_samples_without_lists(const BufferConfig& config, Technique technique) {
  if (config.samples > 1 && !stores_lists(technique))
    throw UsageError("option --samples: " + std::to_string(config.samples) + " samples per pixel need a technique "
                     "that stores lists (a coverage mask per record): " + to_string(technique) + " stores none");
}

TechniqueConfig technique_config(const HashOptions& options) {
  TechniqueConfig c = options.technique;
  c.buffer = options.config;
  return c;
}

HashOptions parse_hash_options(const Args& args, bool techniques) {
  HashOptions o;
  if (techniques) o.technique = parse_technique_options(args);
  const auto screen = args.extent("screen");
  if (!screen) throw UsageError("option --screen is required");
  o.config = parse_buffer_config(args, *screen, args.extent("table").value_or(*screen));
  const BufferConfig& c = o.config;
  if (techniques) refuse_samples_without_lists(c, o.technique.technique);
  // The default thread count is every command's: 0, the default count for
  // the batch (resolve_threads); serial insertion is one thread.
  const std::string mode = args.str("insert-mode");
  o.insert.threads = mode == "serial" ? args.u32("threads", 1, 0, kMaxThreads) : args.u32_in("threads", 0, kMaxThreads);
  const std::optional<InsertMode> parsed = parse_insert_mode(mode);
  if (!parsed) throw UsageError("option --insert-mode: '" + mode + "' is not auto, serial, atomic or owner");
  o.insert.mode = *parsed;
  if (o.insert.mode == InsertMode::Serial && o.insert.threads != 1)
    throw UsageError("--insert-mode serial runs on one thread: give --threads 1");
  if (o.insert.mode == InsertMode::OwnerComputes && !uses_table(o.technique.technique))
    throw UsageError("option --insert-mode owner has no effect with --technique " + to_string(o.technique.technique) +
                     " (owners of table rows: a hash table's own)");
  o.insert.order = insert_order_option(args);
  if (o.insert.order == InsertOrder::Pixel && o.insert.mode == InsertMode::OwnerComputes)
    throw UsageError("option --insert-order pixel cannot go with --insert-mode owner (its owners follow the probes)");
  o.lossless = args.has("lossless");
  o.max_attempts = o.lossless ? args.u32_in("max-attempts", 1, 1000) : 1;
  if (!o.lossless && args.has("max-attempts")) throw UsageError("option --max-attempts needs --lossless");

  const std::string path = args.choice("path");  // the alternatives the command declares
  o.gl = path == "gl";
  o.vk = path == "vk";
  args.refuse_unless(!o.gl && !o.vk, {"threads", "insert-mode", "insert-order"},
                     "with --path " + path + " (the GPU inserts)");

  o.offsets_name = args.str("offsets");
  o.offsets = parse_offset_source(args, c);
  return o;
}


OffsetSource parse_offset_source(const Args& args, const BufferConfig& c) {
  OffsetSource s;
  const std::string name = args.str("offsets");
  s.seed = args.u64_in("seed");
  if (name == "random") {
    s.generator = OffsetGenerator::Random;
  } else if (name == "farthest") {
    s.generator = OffsetGenerator::Farthest;
    if (c.table_or_screen().area() > kFarthestMaxSlots)
      throw UsageError("--offsets farthest: table " + c.table_or_screen().str() + " has more than 2^28 slots");
  } else {
    args.refuse_unless(false, {"seed"}, "with an offsets file (--offsets " + name + ")");
    s.generator = OffsetGenerator::List;
    s.list = read_offset_rows(name);
    // Validate now so the error names the file before any work is done.
    try {
      (void)s.make(c.table_or_screen(), c.record_layout().max_age());
    } catch (const std::invalid_argument& e) {
      throw DataError(name + ": " + e.what());
    }
  }
  return s;
}

}  // namespace habuffer::cli
