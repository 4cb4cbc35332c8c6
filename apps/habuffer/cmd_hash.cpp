// habuffer hash: the coherent hash as a spatial hash table
// (habuffer/spatial/spatial_hash.h): build a table from keys (a CSV, a key
// set, a voxel grid or an image's non-background pixels), query it, print its
// statistics, reconstruct the image it stores.
#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <optional>

#include "cli_args.h"
#include "commands.h"
#include "file_values.h"
#include "habuffer/csv.h"
#include "habuffer/file_roles.h"
#include "habuffer/json_writer.h"
#include "habuffer/fragment_buffer.h"  // kMaxThreads
#include "habuffer/key_streams.h"
#include "habuffer/memory_budget.h"
#include "habuffer/render/image.h"
#include "habuffer/render/voxel_vdb.h"
#include "habuffer/render/voxelizer.h"
#include "habuffer/spatial_hash_file.h"
#include "key_options.h"

namespace habuffer::cli {
namespace {

using spatial::Domain;
using spatial::SpatialHash;

constexpr const char* kHashUsage =
    "usage: habuffer hash build|query|stats|image [OPTIONS]\n"
    "  build   a table from keys: --keys CSV, --key-set NAME, --voxels GRID or --image IMAGE\n"
    "  query   look keys of a CSV up in a table\n"
    "  stats   a table's size, load, ages and memory\n"
    "  image   the image a table built from --image holds, reconstructed\n"
    "Run 'habuffer hash SUBCOMMAND --help' for its options.\n";

}  // namespace

const CommandSpec& hash_build_spec() {
  static const CommandSpec spec{
      "hash build (--keys CSV | --key-set NAME | --voxels GRID | --image IMAGE) --out TABLE [OPTIONS]",
      {{"keys", "CSV", "", "keys with header x,y / x,y,z / x,y,value / x,y,z,value", reads()},
       key_set_option("key-set"),
       {"voxels", "GRID", "", "the solid voxels of a voxel grid file: HAVOXEL1 (voxelize --out) or OpenVDB (voxelize --vdb, "
                              "a bool grid or a float fog volume), told by its first bytes", reads()},
       {"image", "IMAGE", "", "the pixels of an image that differ from --background, valued RGBA8", reads()},
       {"background", "R,G,B", "1,1,1", "(--image) the colour left out, in [0, 1]"},
       {"domain", "XxY[xZ]", "", "the key space; default: the keys' bounds (the image's or grid's size)"},
       coverage_option(),
       count_option(),
       {"out", "TABLE", "", "the table file (HASPATL1; habuffer/spatial_hash_file.h)", writes_creating_parents()},
       {"load", "L", "0.8", "the load the table is sized for, in (0, 1]"},
       {"fixed", "", "", "no adaptive resizing (the table stays sized for --load; lossless growth still)"},
       {"rule", "max|min|first|last", "last", "which value a key given twice keeps"},
       {"age-bits", "A", "8", "age bits of a record, 4..12 (quotients get 31 - A)"},
       {"miss-filter-bits", "0|8|16", "16", "miss filter bits a slot: most absent keys answered in one load (0: none)"},
       {"offsets", "random|farthest", "random", "the probe offsets"},
       {"seed", "S", "1", "the offsets' seed (and the key set's)"},
       {"threads", "N", "0", "inserting threads; 0: the default count"},
       {"stats", "S.json", "", "the build's counters and the table's statistics", writes()},
       {"quiet", "", "", "no summary"}},
      "  Exit codes: 0 ok, 1 bad data (a key file, a grid, an image), 2 bad usage.\n"};
  return spec;
}

const CommandSpec& hash_query_spec() {
  static const CommandSpec spec{
      "hash query --table TABLE --keys CSV [--out RESULTS.csv] [OPTIONS]",
      {{"table", "TABLE", "", "a table file (habuffer hash build --out)", reads()},
       {"keys", "CSV", "", "keys with header x,y or x,y,z (a value column is ignored)", reads()},
       {"out", "RESULTS.csv", "", "x,y[,z],found,value per key, in the file's order", writes()},
       {"threads", "N", "0", "querying threads; 0: the default count"},
       {"quiet", "", "", "no summary"}},
      "  Exit codes: 0 ok, 1 bad data (a key outside the table's domain too), 2 bad usage.\n"};
  return spec;
}

const CommandSpec& hash_stats_spec() {
  static const CommandSpec spec{"hash stats --table TABLE [--out S.json]",
                                {{"table", "TABLE", "", "a table file", reads()},
                                 {"out", "S.json", "", "the statistics as JSON (ages per age included)", writes()}},
                                "  Exit codes: 0 ok, 1 bad data, 2 bad usage.\n"};
  return spec;
}

const CommandSpec& hash_image_spec() {
  static const CommandSpec spec{
      "hash image --table TABLE --out IMAGE [--background R,G,B]",
      {{"table", "TABLE", "", "a table built with --image (values RGBA8)", reads()},
       {"out", "IMAGE", "", "the image: each key's pixel its value, the rest the background", writes_creating_parents()},
       {"background", "R,G,B", "1,1,1", "the colour of pixels not in the table, in [0, 1]"}},
      "  Exit codes: 0 ok, 1 bad data (a 3D table), 2 bad usage.\n"};
  return spec;
}

namespace {

// Every key of a key file in the domain, else DataError naming the file and the data row.
void check_rows(const std::string& path, const std::vector<glm::uvec3>& keys, const spatial::FoldedDomain& domain) {
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (!domain.contains(keys[i]))
      throw DataError(path + ": data row " + std::to_string(i + 1) + ": key (" + std::to_string(keys[i].x) + ", " +
                      std::to_string(keys[i].y) + ", " + std::to_string(keys[i].z) + ") is outside the domain " +
                      domain.domain().str());
}

glm::vec3 parse_colour(const Args& args) {
  const std::vector<std::string> parts = args.list("background");
  if (parts.size() != 3) throw UsageError("option --background: '" + args.str("background") + "' is not R,G,B");
  glm::vec3 c;
  for (int i = 0; i < 3; ++i) {
    char* end = nullptr;
    c[i] = std::strtof(parts[static_cast<std::size_t>(i)].c_str(), &end);
    if (end == parts[static_cast<std::size_t>(i)].c_str() || *end != '\0' || !(c[i] >= 0.0f && c[i] <= 1.0f))
      throw UsageError("option --background: '" + args.str("background") + "' is not three numbers in [0, 1]");
  }
  return c;
}

std::uint32_t rgba8(glm::vec4 c) {
  const auto b = [](float v) { return static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  return b(c.r) << 24 | b(c.g) << 16 | b(c.b) << 8 | b(c.a);
}

void write_table_stats(JsonWriter& json, const spatial::SpatialHashStats& s) {
  json.field("table", s.table.str()).field("slots", s.slots).field("keys", s.keys).field("tombstones", s.tombstones);
  json.field("load", s.load).field("max_age", s.max_age).field("mean_age", s.mean_age);
  json.field("quotient_bits", s.quotient_bits).field("memory_bytes", s.memory_bytes);
  json.field("bytes_per_key", s.bytes_per_key);
  json.key("ages").begin_array();
  for (std::size_t a = 1; a <= s.max_age && a < s.ages.size(); ++a) json.value(s.ages[a]);
  json.end_array();
}

// The table's configuration from build's options.
spatial::SpatialHashConfig parse_build_config(const Args& args) {
  spatial::SpatialHashConfig c;
  const std::optional<spatial::DuplicateRule> rule = spatial::parse_duplicate_rule(args.str("rule"));
  if (!rule) throw UsageError("option --rule: '" + args.str("rule") + "' is not max, min, first or last");
  c.rule = *rule;
  c.age_bits = args.u32_in("age-bits", HABUFFER_SH_MIN_AGE_BITS, HABUFFER_SH_MAX_AGE_BITS);
  const std::optional<OffsetGenerator> offsets = parse_offset_generator(args.str("offsets"));
  if (!offsets) throw UsageError("option --offsets: '" + args.str("offsets") + "' is not random or farthest");
  c.offsets = *offsets;
  c.seed = args.u64_in("seed");
  c.threads = args.u32_in("threads", 0, kMaxThreads);
  c.miss_filter_bits = args.u32_in("miss-filter-bits", 0, 16);
  if (c.miss_filter_bits % 8 != 0)
    throw UsageError("option --miss-filter-bits: " + args.str("miss-filter-bits") + " is not 0, 8 or 16");
  c.target_load = args.real("load");
  if (!(c.target_load > 0.0 && c.target_load <= 1.0))
    throw UsageError("option --load: " + args.str("load") + " is outside (0, 1]");
  c.adaptive = !args.has("fixed");
  if (c.adaptive && c.target_load > c.grow_at) c.grow_at = c.target_load;  // a table sized above 0.8 must not grow at once
  return c;
}

std::string gib_text(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GiB", static_cast<double>(bytes) / static_cast<double>(1u << 30));
  return text;
}

// A table the domain's quotients make past this many slots (1 GiB) and
// kSparseFactor times the slots the keys fill is refused: a record keeps
// 31 - A bits of its key's quotient, so the table has at least about
// Du Dv / 2^(31 - A) slots whatever the keys, and a few keys far from the
// origin (the domain their bounds) would ask for a huge, nearly empty table.
constexpr std::uint64_t kSparseSlots = std::uint64_t{1} << 27;
constexpr double kSparseFactor = 64.0;

// The table build makes for `keys` keys, checked before anything is
// allocated: one that cannot be made, one the domain's quotients make huge
// and nearly empty, or one whose build (two tables at once: the batch's
// deduplication or the saved file's copy beside the table) does not fit the
// machine is refused, naming the sizes and the options that set them.
void check_build_size(const Args& args, const spatial::SpatialHashConfig& c, std::uint64_t keys) {
  const bool given = args.has("domain");
  const std::string domain = "the domain " + c.domain.str() + (given ? " (--domain)" : " (the keys' bounds)");
  spatial::FoldedDomain fold;
  Extent table;
  try {
    fold = spatial::FoldedDomain(c.domain);
    table = SpatialHash::table_for(fold, c.age_bits, keys, c.target_load);
  } catch (const std::invalid_argument& e) {
    throw UsageError("hash build: " + std::string(e.what()) + " (" + domain + ", --age-bits " + args.str("age-bits") +
                     ", --load " + args.str("load") + ")");
  }
  const std::uint64_t bytes = SpatialHash::memory_for(c, table);
  const std::string what = "a table of " + table.str() + " slots for " + std::to_string(keys) +
                           (keys == 1 ? " key" : " keys") + " in " + domain;
  const double filled = std::max(1.0, std::ceil(static_cast<double>(keys) / c.target_load));
  if (table.area() > kSparseSlots && static_cast<double>(table.area()) > kSparseFactor * filled) {
    std::string fewer;
    if (c.age_bits > HABUFFER_SH_MIN_AGE_BITS) {
      spatial::SpatialHashConfig least = c;
      least.age_bits = HABUFFER_SH_MIN_AGE_BITS;
      try {
        const Extent t = SpatialHash::table_for(fold, least.age_bits, keys, c.target_load);
        fewer = " (--age-bits " + std::to_string(least.age_bits) + ": " + t.str() + " slots, " +
                gib_text(SpatialHash::memory_for(least, t)) + ")";
      } catch (const std::invalid_argument&) {
        // no table at the fewest age bits either: the domain alone is the remedy
      }
    }
    char slots[32];
    std::snprintf(slots, sizeof slots, "%.0f", filled);
    throw UsageError("hash build: " + what + " would take " + gib_text(bytes) + " for its quotients to fit " +
                     std::to_string(31u - c.age_bits) + " bits (--age-bits " + std::to_string(c.age_bits) +
                     "), though the keys fill " + slots + " slots at --load " + args.str("load") +
                     ": give a smaller --domain" + (given ? "" : " (keys nearer 0)") + " or fewer --age-bits" + fewer);
  }
  usage_errors("", [&] {
    check_fits_in_memory("hash build: " + what + " (twice: the file's copy; --domain, --age-bits and --load set it)",
                         saturating_product(bytes, 2));
  });
}

// The keys (and values, where the source has them) of build's one source,
// with the domain the source implies (a grid's or image's), if any.
struct BuildKeys {
  std::vector<glm::uvec3> keys;
  std::vector<std::uint32_t> values;
  std::optional<Domain> natural;
};

// A voxel file's solid voxels as keys. The file is read sparse (OpenVDB's
// tiles and blocks, habuffer/render/voxel_vdb.h) and its voxels counted, then
// the keys and the table they need checked against the machine, before any
// voxel is expanded: a 1024^3 tile in a 500-byte file is refused (or built)
// from its count, not after 2^30 voxels were made.
BuildKeys voxel_keys(const Args& args, const spatial::SpatialHashConfig& c, const std::string& path) {
  const SparseVoxels v = read_voxel_file(path);
  BuildKeys k;
  k.natural = Domain{v.n, v.n, v.n};
  const std::uint64_t solid = v.count();
  try {
    check_fits_in_memory(path + ": " + std::to_string(solid) + " solid voxels as keys",
                         saturating_product(solid, sizeof(glm::uvec3)));
  } catch (const std::invalid_argument& e) {
    throw DataError(e.what());
  }
  if (solid == 0) return k;
  spatial::SpatialHashConfig sized = c;
  sized.domain = args.has("domain") ? parse_domain(args.str("domain")) : *k.natural;
  check_build_size(args, sized, solid);
  k.keys.reserve(solid);
  v.for_each([&](std::uint32_t x, std::uint32_t y, std::uint32_t z) { k.keys.emplace_back(x, y, z); });
  return k;
}

BuildKeys image_keys(const Args& args) {
  if (!has_image_support()) throw UsageError("option --image: this habuffer was built without image files");
  const Image image = read_image(args.required("image"));
  const std::uint32_t bg8 = rgba8(glm::vec4(parse_colour(args), 1.0f));
  BuildKeys k;
  k.natural = Domain{image.size.x, image.size.y, 1};
  for (std::uint32_t y = 0; y < image.size.y; ++y)
    for (std::uint32_t x = 0; x < image.size.x; ++x) {
      const std::uint32_t v = rgba8(image.pixels[x + std::size_t{y} * image.size.x]);
      if (v == bg8) continue;
      k.keys.emplace_back(x, y, 0u);
      k.values.push_back(v);
    }
  return k;
}

BuildKeys read_build_keys(const Args& args, const spatial::SpatialHashConfig& c) {
  if (args.has("keys")) {
    spatial::KeyFile f = spatial::read_keys_csv(args.required("keys"));
    return {std::move(f.keys), std::move(f.values), std::nullopt};
  }
  if (args.has("key-set")) return {spatial::make_keys(parse_key_set(args, "key-set", c.seed)), {}, std::nullopt};
  if (args.has("voxels")) return voxel_keys(args, c, args.required("voxels"));
  return image_keys(args);
}

void write_build_stats(const std::string& path, const spatial::SpatialHashConfig& c, const spatial::InsertReport& report,
                       double ms, const spatial::SpatialHashStats& s) {
  JsonWriter json;
  json.begin_object().field("domain", c.domain.str()).field("rule", to_string(c.rule));
  json.field("calls", report.calls).field("stored", report.stored).field("duplicates", report.duplicates);
  json.field("failed_age", report.failed_age).field("failed_iter", report.failed_iter).field("lost", report.lost);
  json.field("rehashes", report.rehashes).field("build_ms", ms);
  write_table_stats(json, s);
  json.end_object();
  json.save(path);
}

int run_build(const std::vector<std::string>& argv) {
  if (print_help(argv, hash_build_spec())) return 0;
  const Args args(argv, hash_build_spec());
  const int sources = int{args.has("keys")} + int{args.has("key-set")} + int{args.has("voxels")} + int{args.has("image")};
  if (sources != 1) throw UsageError("give exactly one of --keys, --key-set, --voxels and --image");
  args.refuse_unless(args.has("key-set"), {"coverage", "count"}, "without --key-set");
  args.refuse_unless(args.has("image"), {"background"}, "without --image");

  spatial::SpatialHashConfig c = parse_build_config(args);
  const BuildKeys k = read_build_keys(args, c);
  c.domain = args.has("domain") ? parse_domain(args.str("domain")) : k.natural ? *k.natural : spatial::domain_of(k.keys);
  if (k.keys.empty()) throw DataError("hash build: no keys (nothing to store)");
  if (args.has("keys")) check_rows(args.required("keys"), k.keys, spatial::FoldedDomain(c.domain));
  check_build_size(args, c, k.keys.size());

  const auto t0 = std::chrono::steady_clock::now();
  SpatialHash table(c, k.keys.size());
  spatial::InsertReport report;
  try {
    report = table.insert(k.keys, k.values);
  } catch (const std::invalid_argument& e) {
    throw DataError(std::string("hash build: ") + e.what());
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  spatial::save_spatial_hash(args.required("out"), table);
  const spatial::SpatialHashStats s = table.stats();
  if (args.has("stats")) write_build_stats(args.required("stats"), c, report, ms, s);
  if (!args.has("quiet"))
    std::printf("%llu keys (%llu duplicates) in a %s table of domain %s: load %.3f, mean age %.2f, max age %u, "
                "%.2f bytes per key, %u rehashes, %.1f ms\n",
                static_cast<unsigned long long>(s.keys), static_cast<unsigned long long>(report.duplicates),
                s.table.str().c_str(), c.domain.str().c_str(), s.load, s.mean_age, s.max_age, s.bytes_per_key,
                report.rehashes, ms);
  return 0;
}

int run_query(const std::vector<std::string>& argv) {
  if (print_help(argv, hash_query_spec())) return 0;
  const Args args(argv, hash_query_spec());
  SpatialHash table = spatial::load_spatial_hash(args.required("table"));
  const spatial::KeyFile f = spatial::read_keys_csv(args.required("keys"));
  check_rows(args.required("keys"), f.keys, table.domain());
  table.set_threads(args.u32_in("threads", 0, kMaxThreads));  // the batched find's (a table file keeps none)
  std::vector<std::uint32_t> values(f.keys.size());
  std::vector<std::uint8_t> found(f.keys.size());
  const auto t0 = std::chrono::steady_clock::now();
  std::uint64_t hits = 0;
  try {
    hits = table.find(f.keys, values, found);
  } catch (const std::invalid_argument& e) {
    throw DataError(args.required("keys") + ": " + e.what());
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (args.has("out")) {
    CsvWriter out(args.required("out"));
    out.text(f.three_d ? "x,y,z,found,value" : "x,y,found,value").endl();
    for (std::size_t i = 0; i < f.keys.size(); ++i) {
      out.u64(f.keys[i].x).comma().u64(f.keys[i].y).comma();
      if (f.three_d) out.u64(f.keys[i].z).comma();
      out.u64(found[i]).comma().u64(values[i]).endl();
    }
    out.close();
  }
  if (!args.has("quiet"))
    std::printf("%llu keys: %llu found, %llu absent, %.1f ms (%.1f M lookups/s)\n",
                static_cast<unsigned long long>(f.keys.size()), static_cast<unsigned long long>(hits),
                static_cast<unsigned long long>(f.keys.size() - hits), ms,
                ms > 0.0 ? static_cast<double>(f.keys.size()) / ms / 1000.0 : 0.0);
  return 0;
}

int run_hash_stats(const std::vector<std::string>& argv) {
  if (print_help(argv, hash_stats_spec())) return 0;
  const Args args(argv, hash_stats_spec());
  const SpatialHash table = spatial::load_spatial_hash(args.required("table"));
  const spatial::SpatialHashStats s = table.stats();
  if (args.has("out")) {
    JsonWriter json;
    json.begin_object().field("domain", table.config().domain.str()).field("rule", to_string(table.config().rule));
    json.field("age_bits", table.config().age_bits);
    write_table_stats(json, s);
    json.end_object();
    json.save(args.required("out"));
  }
  std::printf("domain %s, table %s (%llu slots): %llu keys, %llu tombstones, load %.3f, mean age %.2f, max age %u, "
              "quotient bits %u, %.2f bytes per key\n",
              table.config().domain.str().c_str(), s.table.str().c_str(), static_cast<unsigned long long>(s.slots),
              static_cast<unsigned long long>(s.keys), static_cast<unsigned long long>(s.tombstones), s.load,
              s.mean_age, s.max_age, s.quotient_bits, s.bytes_per_key);
  return 0;
}

int run_hash_image(const std::vector<std::string>& argv) {
  if (print_help(argv, hash_image_spec())) return 0;
  const Args args(argv, hash_image_spec());
  if (!has_image_support()) throw UsageError("hash image: this habuffer was built without image files");
  usage_errors("out", [&] { check_image_extension(args.required("out")); });  // before the table is read
  const SpatialHash table = spatial::load_spatial_hash(args.required("table"));
  const Domain d = table.config().domain;
  if (d.z != 1) throw DataError("hash image: the table's domain " + d.str() + " is 3D, not an image");
  try {  // the pixels (RGBA floats) and the writer's RGB copies of them
    check_fits_in_memory("hash image: the table's domain " + d.str() + " as an image",
                         saturating_product(std::uint64_t{d.x} * d.y, 16 + 2 * 12));
  } catch (const std::invalid_argument& e) {
    throw DataError(e.what());
  }
  const glm::vec3 bg = parse_colour(args);
  Image image{{d.x, d.y}, std::vector<glm::vec4>(std::size_t{d.x} * d.y, glm::vec4(bg, 1.0f))};
  table.for_each([&](const spatial::Entry& e) {
    const std::uint32_t v = e.value;
    image.pixels[e.key.x + std::size_t{e.key.y} * d.x] =
        glm::vec4(static_cast<float>(v >> 24) / 255.0f, static_cast<float>(v >> 16 & 255u) / 255.0f,
                  static_cast<float>(v >> 8 & 255u) / 255.0f, static_cast<float>(v & 255u) / 255.0f);
  });
  write_image(args.required("out"), image);
  return 0;
}

}  // namespace

int run_hash(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0] == "--help" || argv[0] == "-h") {
    std::fputs(kHashUsage, argv.empty() ? stderr : stdout);
    return argv.empty() ? 2 : 0;
  }
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (argv[0] == "build") return run_build(rest);
  if (argv[0] == "query") return run_query(rest);
  if (argv[0] == "stats") return run_hash_stats(rest);
  if (argv[0] == "image") return run_hash_image(rest);
  throw UsageError("unknown subcommand '" + argv[0] + "' (build, query, stats or image)");
}

}  // namespace habuffer::cli
