#include "harness_cli.h"

#include <cstdio>

#include "habuffer/csv.h"
#include "habuffer/gl/gl_error.h"

namespace habuffer::cli {

std::vector<double> parse_reals(const Args& args, const std::string& name, const std::string& fallback, double lo,
                                double hi) {
  std::vector<double> out;
  for (const std::string& w : args.list(name, fallback)) {
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
  const std::string p = args.str("path", "gl");
  if (p != "gl" && p != "cpu") throw UsageError("--path must be gl or cpu, not '" + p + "'");
  return p == "gl" ? RenderPath::Gl : RenderPath::Cpu;
}

std::vector<Extent> parse_sizes(const Args& args, const std::string& fallback) {
  std::vector<Extent> out;
  for (const std::string& w : args.list("size", fallback)) {
    const std::optional<Extent> e = parse_extent(w);
    if (!e) throw UsageError("--size: '" + w + "' is not WxH with positive sides");
    out.push_back(*e);
  }
  return out;
}

namespace {

// Each word of the list option `name` through `parse`; a word it refuses
// becomes a UsageError naming the option.
template <class Parse>
auto parse_words(const Args& args, const std::string& name, const std::string& fallback, Parse parse) {
  std::vector<decltype(parse(std::string{}))> out;
  try {
    for (const std::string& w : args.list(name, fallback)) out.push_back(parse(w));
  } catch (const std::invalid_argument& e) {
    throw UsageError("--" + name + ": " + e.what());
  }
  return out;
}

}  // namespace

std::vector<harness::TechniqueSpec> parse_techniques(const Args& args, const std::string& name,
                                                     const std::string& fallback) {
  return parse_words(args, name, fallback, harness::parse_technique_spec);
}

std::vector<harness::WorkloadSpec> parse_scenes(const Args& args, const std::string& name) {
  return parse_scenes_or(args, name, "");
}

std::vector<harness::WorkloadSpec> parse_scenes_or(const Args& args, const std::string& name, const std::string& fallback) {
  return parse_words(args, name, fallback, harness::parse_workload_spec);
}

std::vector<std::string> parse_outputs(const Args& args, const std::vector<std::string>& inputs) {
  const std::vector<std::string> outputs = args.list("out", "");
  try {
    harness::check_table_paths(outputs);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
  FileRoles files;
  for (const std::string& in : inputs) files.input("input", in);
  for (const std::string& out : outputs) files.output("--out", out);
  check_files(files);
  return outputs;
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

void write_outputs(const char* command, harness::ResultTable& table, const std::vector<std::string>& outputs,
                   const std::vector<std::string>& argv) {
  const std::string renderer = table.provenance.renderer;
  table.provenance = provenance(command, argv);
  table.provenance.renderer = renderer;
  harness::write_table(table, outputs);
  for (const std::string& o : outputs)
    std::printf("habuffer %s: %zu rows to %s\n", command, table.rows.size(), o.c_str());
}

}  // namespace habuffer::cli
