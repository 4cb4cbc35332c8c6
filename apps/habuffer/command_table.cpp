// The CLI's commands in one table: their runners (main dispatches by it) and
// their declarations (the tests walk every command's options and files).
#include "cli_args.h"
#include "commands.h"

namespace habuffer::cli {

const std::map<std::string, int (*)(const std::vector<std::string>&)>& command_runners() {
  static const std::map<std::string, int (*)(const std::vector<std::string>&)> commands{
      {"build-lists", run_build_lists}, {"generate", run_generate}, {"offsets", run_offsets},
      {"demo", run_demo},               {"info", run_info},         {"stats", run_stats},
      {"render", run_render},           {"compare", run_compare},   {"sweep", run_sweep},
      {"bench", run_bench},             {"figure", run_figure},     {"plan", run_plan},
      {"techniques", run_techniques},   {"voxelize", run_voxelize}, {"csg", run_csg},
      {"hash", run_hash}};
  return commands;
}

std::vector<std::pair<std::string, const CommandSpec*>> all_command_specs() {
  std::vector<std::pair<std::string, const CommandSpec*>> out{
      {"build-lists", &build_lists_spec()}, {"generate", &generate_spec()},    {"offsets", &offsets_spec()},
      {"demo", &demo_spec()},               {"info", &info_spec()},            {"stats", &stats_spec()},
      {"render", &render_spec()},           {"compare", &compare_spec()},      {"sweep", &sweep_spec()},
      {"bench", &bench_spec()},             {"plan", &plan_spec()},            {"techniques", &techniques_spec()},
      {"voxelize", &voxelize_spec()},       {"csg", &csg_spec()},              {"hash build", &hash_build_spec()},
      {"hash query", &hash_query_spec()},   {"hash stats", &hash_stats_spec()}, {"hash image", &hash_image_spec()}};
  for (const auto& [name, spec] : figure_specs()) out.emplace_back(name, &spec);
  return out;
}

}  // namespace habuffer::cli
