// habuffer build-lists: fragment CSV in, per-pixel sorted lists out.
#include <chrono>
#include <cstdio>

#include "commands.h"
#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_ha_buffer.h"
#include "habuffer/interchange.h"
#include "hash_options.h"
#include "report_json.h"

namespace habuffer::cli {
namespace {

constexpr const char* kHelp =
    "usage: habuffer build-lists --in FRAGS.csv --out LISTS.csv --screen WxH [--table WxH] [--layout 64|32]\n"
    "         [--age-bits N] [--offsets random|farthest|OFFSETS.csv] [--seed N] [--block B] [--threads N]\n"
    "         [--early-cull TAU] [--lossless [--max-attempts N]] [--iter-limit N] [--stats STATS.json]\n"
    "         [--insert-mode auto|serial|atomic|owner] [--path cpu|gl]\n"
    "         [--dump-table TABLE.csv] [--dump-max-age MAXAGE.csv]\n"
    "  --threads 0 uses every hardware thread; every insert mode builds the same table. Exit codes: 0 ok, 1 bad data or lossless failure, 2 bad usage.\n";

// The GPU path: a headless context, one frame of compute insertion (lossless
// mode regathers on the GPU), and the read-back imported into a CPU-side
// buffer so lists and dumps are written the same way.
// Sets timing.build_ms to the insertion alone (upload, every gather, counters),
// without the context's creation and the shader compilation.
BuildResult build_on_gl(const HashOptions& options, std::span<const Fragment> fragments, BuildTiming& timing) {
  std::optional<gl::EglContext> context;
  try {
    context.emplace();
  } catch (const gl::GlError& e) {
    throw DataError(std::string("--path gl: no usable OpenGL: ") + e.what());
  }
  const BufferConfig& c = options.config;
  const gl::GlInfo info = gl::query_gl_info();
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(info, c.layout);
  if (!mode) throw DataError("--path gl --layout 64: this OpenGL has no 64-bit shader types (GL_ARB_gpu_shader_int64)");
  gl::GlFrameOptions frame_options;
  frame_options.policy = options.policy;
  frame_options.max_attempts = options.max_attempts;
  gl::GlHaBuffer gpu(c, options.offsets, *mode, frame_options);
  gl::ComputeInserter inserter(gpu);
  const auto t0 = std::chrono::steady_clock::now();
  gl::FrameReport report = inserter.insert(fragments);
  timing.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  timing.gl_atomic_mode = gl::to_string(*mode);
  timing.gl_renderer = info.renderer;
  timing.gl_deferred = report.deferred;
  timing.gl_resume_rounds = report.resume_rounds;
  timing.gl_cut_short_retries = report.cut_short_retries;
  HaBuffer buffer(gpu.config(), gpu.offsets());
  buffer.import_state(gpu.read_table(), gpu.read_max_age());
  return BuildResult{std::move(buffer), report.counters, std::move(report.attempts)};
}

}  // namespace

int run_build_lists(const std::vector<std::string>& argv) {
  if (print_help(argv, kHelp)) return 0;
  auto valued = hash_valued_options();
  valued.insert({"in", "out", "stats", "dump-table", "dump-max-age"});
  const Args args(argv, valued, hash_flag_options());
  const std::string in = args.required("in");
  const std::string out = args.required("out");
  const HashOptions options = parse_hash_options(args);

  const std::vector<Fragment> fragments = read_fragments(in, options.config.screen);
  BuildTiming timing{0.0, resolved_threads(options.insert.threads), {}, {}};
  std::optional<BuildResult> built;
  if (options.gl) {
    built.emplace(build_on_gl(options, fragments, timing));
  } else {
    const auto t0 = std::chrono::steady_clock::now();
    built.emplace(build(options.config, options.offsets, fragments, options.insert, options.policy, options.max_attempts));
    timing.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  BuildResult& result = *built;

  write_lists(out, result.buffer);
  if (args.has("dump-table")) write_table(args.required("dump-table"), result.buffer);
  if (args.has("dump-max-age")) write_max_age(args.required("dump-max-age"), result.buffer);
  const BuildReport report = summarize(result.buffer, result.counters);
  if (args.has("stats")) {
    JsonWriter json;
    json.begin_object();
    json.field("in", in);
    write_build_stats(json, options, result, report, timing);
    json.end_object();
    json.save(args.required("stats"));
  }
  if (report.stored != report.counters.stored())
    throw std::logic_error("accounting broken: table holds " + std::to_string(report.stored) +
                           " records, counters say " + std::to_string(report.counters.stored()));
  if (options.lossless && !result.lossless()) {
    std::fprintf(stderr,
                 "habuffer build-lists: lossless mode: %llu fragments still failed after %zu attempts "
                 "(last table %s, AMAX %u); a pixel with more than AMAX distinct fragments needs more --age-bits\n",
                 static_cast<unsigned long long>(result.counters.failures()), result.attempts.size(),
                 result.buffer.table().str().c_str(), options.config.record_layout().max_age());
    return 1;
  }
  return 0;
}

}  // namespace habuffer::cli
