// habuffer generate: a synthetic fragment stream as CSV.
#include <cmath>
#include <cstdio>

#include "cli_args.h"
#include "commands.h"
#include "file_values.h"
#include "habuffer/fragment_streams.h"
#include "habuffer/interchange.h"
#include "habuffer/memory_budget.h"

namespace habuffer::cli {

const CommandSpec& generate_spec() {
  static const CommandSpec spec{
      "generate --screen WxH --out FRAGS.csv (--fragments N | --load L [--table WxH]) [OPTIONS]",
      {{"screen", "WxH", "", "the screen the fragments fall on (required)"},
       {"out", "FRAGS.csv", "", "the fragment stream (required)", writes()},
       {"stream", "coherent|random", "coherent", "the stream's shape"},
       {"fragments", "N", "", "this many fragments"},
       {"load", "L", "", "as many fragments as fill L of the table's slots, L in (0, 4]"},
       {"table", "WxH", "", "the table --load fills (default: the screen)"},
       {"seed", "N", "1", "the stream's seed"},
       {"min-side", "S", std::to_string(StreamOptions{}.min_side), "coherent: the smallest rectangle side"},
       {"max-side", "S", std::to_string(StreamOptions{}.max_side), "coherent: the largest rectangle side"}},
      ""};
  return spec;
}

int run_generate(const std::vector<std::string>& argv) {
  if (print_help(argv, generate_spec())) return 0;
  const Args args(argv, generate_spec());
  const auto screen = args.extent("screen");
  if (!screen) throw UsageError("option --screen is required");
  const std::string out = args.required("out");
  StreamOptions o;
  try {
    o.kind = parse_stream_kind(args.str("stream"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("option --stream: ") + e.what());
  }
  o.seed = args.u64_in("seed");
  args.refuse_unless(o.kind == StreamKind::Coherent, {"min-side", "max-side"}, "on a --stream other than coherent");
  args.refuse_unless(args.has("load"), {"table"}, "without --load");
  o.min_side = args.u32_in("min-side", 1);
  if (!args.has("max-side") && o.max_side < o.min_side)
    throw UsageError("option --min-side: " + std::to_string(o.min_side) + " is above the default --max-side " +
                     std::to_string(o.max_side) + ": give --max-side too");
  o.max_side = args.u32_in("max-side", o.min_side);
  if (args.has("fragments") == args.has("load")) throw UsageError("give exactly one of --fragments and --load");
  if (args.has("fragments")) {
    o.count = args.u64("fragments", 0, 0, std::uint64_t{1} << 34);
  } else {
    const double load = args.real("load", 0.0);
    if (!(load > 0.0 && load <= 4.0)) throw UsageError("option --load: must be in (0, 4]");
    const Extent table = args.extent("table").value_or(*screen);
    o.count = static_cast<std::uint64_t>(std::llround(load * static_cast<double>(table.area())));
    if (o.count == 0)
      throw UsageError("option --load: " + args.str("load", "") + " of table " + table.str() +
                       " gives no fragment (at least " + shortest(0.5 / static_cast<double>(table.area())) + ")");
  }
  usage_errors("", [&] {
    check_fits_in_memory("--fragments " + std::to_string(o.count), saturating_product(o.count, sizeof(Fragment)));
  });
  write_fragments(out, make_stream(*screen, o));
  return 0;
}

}  // namespace habuffer::cli
