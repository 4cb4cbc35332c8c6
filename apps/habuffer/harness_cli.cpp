#include "harness_cli.h"

#include <algorithm>
#include <cstdio>

#include "habuffer/csv.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/memory_budget.h"
#include "habuffer/printable.h"
#include "habuffer/technique_options.h"
#include "file_values.h"
#include "hash_options.h"
#include "loss_report.h"
#include "vulkan_path.h"

namespace habuffer::cli {

std::vector<OptionSpec> harness_options(std::initializer_list<std::string_view> names) {
  static const std::vector<OptionSpec> own{
      {"out", "F.json[,F.csv]", "", "the table, JSON and/or CSV by extension (required)", writes_in(listed_files, "{}")},
      {"size", "WxH", "256x256", "the image (a harness command renders many times; render's default is 1024x1024)"},
      {"path", kHasVulkanPath ? "gl|cpu|vk" : "gl|cpu", "gl",
       kHasVulkanPath ? "rasterize and insert on the GPU; or GL rasterizes and the CPU or a Vulkan device inserts and "
                        "composites"
                      : "rasterize and insert on the GPU, or insert on the CPU"},
      {"repeats", "N", "3", "runs of each combination (medians, min and max)"},
      {"quiet", "", "", "no progress bar (shown on stderr on a terminal)"},
  };
  std::vector<OptionSpec> out;
  for (std::string_view name : names) {
    const auto it = std::find_if(own.begin(), own.end(), [&](const OptionSpec& o) { return o.name == name; });
    out.push_back(it != own.end() ? *it : shared_options({name}).front());
  }
  return out;
}

std::string technique_knob_help() {
  std::string s;
  for (const TechniqueOption& o : technique_options()) {
    if (o.knob.empty()) continue;
    const TechniqueOption* needed = o.needs.empty() ? nullptr : find_option_flag(o.needs);
    s += help_row("     " + knob_usage(o), std::string(o.help) + " [" + techniques_taking_knob(o) + "]" +
                                               (needed != nullptr ? " (with " + knob_usage(*needed) + ")" : ""));
  }
  return s;
}

std::vector<double> parse_reals(const Args& args, const std::string& name, double lo, double hi) {
  std::vector<double> out;
  for (const std::string& w : args.list(name)) {
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (end != w.c_str() + w.size() || !(v >= lo && v <= hi))
      throw UsageError("--" + name + ": '" + w + "' is not a number" +
                       (lo > -1e300 || hi < 1e300 ? " in [" + shortest(lo) + ", " + shortest(hi) + "]" : std::string()));
    out.push_back(v);
  }
  return out;
}

RenderPath parse_path(const Args& args) {
  const std::string p = args.choice("path");  // the alternatives harness_options declares
  return p == "gl" ? RenderPath::Gl : p == "vk" ? RenderPath::Vk : RenderPath::Cpu;
}

std::vector<Extent> parse_sizes(const Args& args) {
  std::vector<Extent> out;
  for (const std::string& w : args.list("size")) {
    const std::optional<Extent> e = parse_extent(w);
    if (!e) throw UsageError("--size: '" + w + "' is not WxH with positive sides");
    // The least a render allocates: 32 bytes a pixel over its buffers.
    usage_errors("", [&] { check_fits_in_memory("--size " + e->str(), saturating_product(e->area(), 32)); });
    out.push_back(*e);
  }
  return out;
}

namespace {

// Each word of the list option `name` through `parse`; a word it refuses
// becomes a UsageError naming the option.
template <class Parse>
auto parse_words(const Args& args, const std::string& name, Parse parse) {
  std::vector<decltype(parse(std::string{}))> out;
  try {
    for (const std::string& w : args.list(name)) out.push_back(parse(w));
  } catch (const std::invalid_argument& e) {
    throw UsageError("--" + name + ": " + e.what());
  }
  return out;
}

}  // namespace

std::vector<harness::TechniqueSpec> parse_techniques(const Args& args, const std::string& name) {
  return parse_words(args, name, harness::parse_technique_spec);
}

harness::WorkloadSpec parse_scene(const Args& args, const std::string& name) {
  try {
    return harness::parse_workload_spec(args.str(name));
  } catch (const std::invalid_argument& e) {
    throw UsageError("--" + name + ": " + e.what());
  }
}

std::vector<harness::WorkloadSpec> parse_scenes(const Args& args, const std::string& name) {
  return parse_words(args, name, harness::parse_workload_spec);
}

namespace {

std::vector<std::string> table_paths(const Args& args, const std::string& name) {
  if (!args.has(name) && name != "out") return {};
  const std::vector<std::string> paths = args.list(name, "");
  try {
    harness::check_table_paths(paths);
  } catch (const std::invalid_argument& e) {
    throw UsageError("--" + name + ": " + e.what());
  }
  return paths;
}

}  // namespace

HarnessOutputs parse_outputs(const Args& args) {
  HarnessOutputs o{table_paths(args, "out"), table_paths(args, "picks")};
  return o;
}

std::unique_ptr<gl::EglContext> context_for(bool needed, const char* command) {
  std::unique_ptr<gl::EglContext> context;
  if (!needed) return context;
  try {
    context = std::make_unique<gl::EglContext>();
  } catch (const gl::GlError& e) {
    throw DataError(std::string(command) + ": no usable OpenGL: " + e.what());
  }
  return context;
}

harness::Provenance provenance(const char* command, const std::vector<std::string>& argv) {
  harness::Provenance p;
  p.command = std::string("habuffer ") + command;
  for (const std::string& a : argv) p.command += " " + a;
  p.machine = harness::machine_description();
  return p;
}

namespace {

// "technique=lists scene=quads load=0.5": the cells that tell runs apart.
std::string row_label(const harness::ResultRow& row) {
  std::string label;
  for (const char* column : {"technique", "scene", "size", "load", "opacity", "early_cull", "frame"}) {
    const harness::Cell* c = row.find(column);
    if (c == nullptr) continue;
    std::string v;
    if (const auto* t = std::get_if<std::string>(c)) v = *t;
    else if (const auto* i = std::get_if<std::int64_t>(c)) v = std::to_string(*i);
    else if (const auto* d = std::get_if<double>(c)) v = shortest(*d);
    else continue;
    if (!label.empty()) label += ' ';
    label.append(column).append(1, '=').append(v);
  }
  return label;
}

}  // namespace

void warn_table_losses(const char* command, const harness::ResultTable& table) {
  std::size_t lossy = 0, runs = 0;
  std::string first;
  for (const harness::ResultRow& row : table.rows) {
    const std::optional<Counters> c = counters_of(row);
    if (!c) continue;
    ++runs;
    if (lost_fragments(*c) == 0) continue;
    if (lossy++ == 0) first = row_label(row) + ": " + loss_summary(*c);
  }
  if (lossy == 0) return;
  const std::string which = lossy > 1 ? "the first, " + first : first;
  std::fprintf(stderr, "habuffer %s: warning: %zu of %zu runs lost fragments (their counter columns say which); %s\n",
               command, lossy, runs, which.c_str());
}

void write_outputs(const char* command, harness::ResultTable& table, const std::vector<std::string>& outputs,
                   const std::vector<std::string>& argv) {
  warn_table_losses(command, table);
  const std::string renderer = table.provenance.renderer;
  table.provenance = provenance(command, argv);
  table.provenance.renderer = renderer;
  harness::write_table(table, outputs);
  for (const std::string& o : outputs)
    std::printf("habuffer %s: %zu rows to %s\n", command, table.rows.size(), o.c_str());
}

}  // namespace habuffer::cli
