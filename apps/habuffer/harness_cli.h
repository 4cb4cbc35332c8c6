/// @file
/// What the harness commands (sweep, bench, figure, plan) share on the
/// command line: lists of scenes, techniques and sizes, the output files, the
/// GL context, progress and the provenance every table carries, so the four
/// commands read their options and write their tables by one set of rules.
#pragma once

#include <initializer_list>
#include <memory>
#include <string_view>
#include <optional>
#include <string>
#include <vector>

#include "cli_args.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/harness/result_table.h"
#include "habuffer/harness/technique_spec.h"
#include "habuffer/harness/workload.h"

namespace habuffer::cli {

/// The declarations the harness commands share, picked by name (each
/// declared once): --out, --size (256x256: a harness command renders many
/// times; render's one image is 1024x1024), --path (gl, as render's),
/// --repeats, --quiet; the build commands' shared ones (shared_options:
/// --seed, --threads, --insert-order, ...) by the same call.
std::vector<OptionSpec> harness_options(std::initializer_list<std::string_view> names);

/// The technique words' knobs, one help line each ("     cull=TAU  early
/// cull: ... [ha, sorted-lists]"), from the technique option table.
std::string technique_knob_help();

/// Option `name`'s comma-separated list of numbers (its declared default when absent), each in [lo, hi];
/// UsageError otherwise.
std::vector<double> parse_reals(const Args& args, const std::string& name, double lo = -1e300, double hi = 1e300);
/// --path gl|cpu|vk (vk where the CLI has the Vulkan path; its declared default).
RenderPath parse_path(const Args& args);
/// --size WxH[,WxH...] (its declared default when absent): at least one, each positive.
std::vector<Extent> parse_sizes(const Args& args);
/// Option `name`'s technique words (harness/technique_spec.h), its declared default when absent; UsageError
/// naming the option for a bad word.
std::vector<harness::TechniqueSpec> parse_techniques(const Args& args, const std::string& name);
/// Option `name`'s scene words (harness/workload.h), its declared default when absent; UsageError naming the
/// option for a bad word or none.
/// Option `name` as one scene word, the value whole (a file name's commas
/// are its own); UsageError "--NAME: ..." for a bad word.
harness::WorkloadSpec parse_scene(const Args& args, const std::string& name);
std::vector<harness::WorkloadSpec> parse_scenes(const Args& args, const std::string& name);
/// A harness command's files, checked together before any work (one rule
/// for every command): --out F.json[,F.csv] and, where the command has it,
/// --picks F.json[,F.csv] (extensions, writable, no two the same file), none
/// of them any workload's input (a fragment CSV or mesh file).
struct HarnessOutputs {
  std::vector<std::string> out, picks;  ///< --out's and --picks' paths (picks empty when not given)
};
/// Reads and checks --out and --picks (see HarnessOutputs; their files are checked by their declared roles).
HarnessOutputs parse_outputs(const Args& args);

/// A context when any scene needs one (streams do not); DataError when none can be made.
std::unique_ptr<gl::EglContext> context_for(bool needed, const char* command);
/// "habuffer CMD ARGS..." as typed, and the machine.
harness::Provenance provenance(const char* command, const std::vector<std::string>& argv);
/// One warning line on stderr when any run of the table lost fragments
/// (failed, dropped, culled or invalid), naming the first such run.
void warn_table_losses(const char* command, const harness::ResultTable& table);
/// Warns of losses, writes the table and prints one line per output.
void write_outputs(const char* command, harness::ResultTable& table, const std::vector<std::string>& outputs,
                   const std::vector<std::string>& argv);

}  // namespace habuffer::cli
