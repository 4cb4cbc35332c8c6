/// @file
/// The subcommands of the habuffer CLI. Each returns the process exit code:
/// 0 success, 1 bad data, 2 bad usage (errors are thrown, main reports them).
/// `args` are the arguments after the subcommand's name; each prints its usage for a lone --help.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace habuffer::cli {

struct CommandSpec;

int run_build_lists(const std::vector<std::string>& args);  ///< `habuffer build-lists`
int run_generate(const std::vector<std::string>& args);  ///< `habuffer generate`
int run_offsets(const std::vector<std::string>& args);  ///< `habuffer offsets`
int run_demo(const std::vector<std::string>& args);  ///< `habuffer demo`
int run_info(const std::vector<std::string>& args);  ///< `habuffer info`
int run_stats(const std::vector<std::string>& args);  ///< `habuffer stats`
int run_render(const std::vector<std::string>& args);  ///< `habuffer render`
int run_compare(const std::vector<std::string>& args);  ///< `habuffer compare`
int run_sweep(const std::vector<std::string>& args);  ///< `habuffer sweep`
int run_bench(const std::vector<std::string>& args);  ///< `habuffer bench`
int run_figure(const std::vector<std::string>& args);  ///< `habuffer figure`
int run_plan(const std::vector<std::string>& args);  ///< `habuffer plan`
int run_techniques(const std::vector<std::string>& args);  ///< `habuffer techniques`
int run_voxelize(const std::vector<std::string>& args);  ///< `habuffer voxelize`
int run_csg(const std::vector<std::string>& args);  ///< `habuffer csg`
int run_hash(const std::vector<std::string>& args);  ///< `habuffer hash`


/// The declarations behind each command (its options and their file roles),
/// for help and for the tests that walk every command.
const CommandSpec& build_lists_spec();
const CommandSpec& generate_spec();
const CommandSpec& offsets_spec();
const CommandSpec& demo_spec();
const CommandSpec& info_spec();
const CommandSpec& stats_spec();
const CommandSpec& render_spec();
const CommandSpec& compare_spec();
const CommandSpec& sweep_spec();
const CommandSpec& bench_spec();
const CommandSpec& plan_spec();
const CommandSpec& techniques_spec();
const CommandSpec& voxelize_spec();
const CommandSpec& csg_spec();
const CommandSpec& hash_build_spec();
const CommandSpec& hash_query_spec();
const CommandSpec& hash_stats_spec();
const CommandSpec& hash_image_spec();
/// One spec per figure ("figure NAME"), as run_figure parses it.
const std::vector<std::pair<std::string, CommandSpec>>& figure_specs();

/// The commands by name, as main dispatches them.
const std::map<std::string, int (*)(const std::vector<std::string>&)>& command_runners();

/// Every command's and subcommand's spec by its command line ("render", "hash build", "figure voxels").
std::vector<std::pair<std::string, const CommandSpec*>> all_command_specs();

}  // namespace habuffer::cli
