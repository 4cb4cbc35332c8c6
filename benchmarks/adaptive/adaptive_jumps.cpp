// habuffer_adaptive_jumps: the figures of issue 45 on this machine's GL
// (llvmpipe here, a GPU where there is one): a host whose depth complexity
// jumps and drops in one frame, run through the frame driver as an engine
// embeds it (an automatic HA-buffer table, full-screen layers of distinct
// depths as the gather), in each readback mode. Per scenario: frames that
// lost fragments, fragments lost, gathers in the jump's frame, the jump
// frame's wall time against a normal frame's, frames until the memory is
// back after a drop; and the cost of a steady frame in each mode.
//
// Usage: habuffer_adaptive_jumps [--size N] [--repeats R] [--late-rounds N]
// (docs/performance.md's "before" figures came from this file as of commit
// 59ad1ca, built against the commit before issue 45 with its
// HABUFFER_ADAPTIVE_OLD_API switch.)
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "habuffer/fragment_streams.h"
#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/lossless_build.h"

namespace hb = habuffer;

namespace {

std::uint32_t g_late_rounds = 8;  // --late-rounds: GlFrameOptions::late_resume_rounds

// native64 where the GPU has 64-bit atomics, else emulated64 (llvmpipe).
hb::gl::AtomicMode mode() {
  const auto modes = hb::gl::runnable_atomic_modes(hb::gl::query_gl_info());
  return std::find(modes.begin(), modes.end(), hb::gl::AtomicMode::Native64) != modes.end()
             ? hb::gl::AtomicMode::Native64
             : hb::gl::AtomicMode::Emulated64;
}

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

struct FrameFigures {
  double ms = 0;                 // wall time of frame() (deferred: submission; the tail waits at the end)
  std::uint64_t lost = 0;        // fragments lost (its complete report)
  std::uint64_t gathers = 0;     // attempts
  std::uint64_t capacity = 0;    // slots it was gathered into (the final attempt's)
};

// The frames of `script` (layers per frame) through one driver; each
// frame's complete figures (Deferred: gathered from the late reports).
std::vector<FrameFigures> run(hb::Extent screen, const std::vector<int>& script, bool deferred) {
  hb::gl::GlFrameOptions o;
  if (deferred) o.readback = hb::gl::Readback::Deferred;
  o.late_resume_rounds = g_late_rounds;
  hb::BufferConfig c;
  c.screen = screen;  // table unset: automatic
  hb::gl::GlHaBuffer gpu(c, hb::OffsetSource{}, mode(), o);
  hb::gl::ComputeInserter inserter(gpu);
  std::vector<FrameFigures> out(script.size());
  const auto take = [&](const hb::gl::FrameReport& r) {
    FrameFigures& f = out[r.index];
    f.lost = r.counters.failures();
    f.gathers = r.attempts.size();
    f.capacity = r.capacity;
  };
  for (std::size_t k = 0; k < script.size(); ++k) {
    const std::vector<hb::Fragment> frags =
        hb::layered_stream(screen, static_cast<std::uint32_t>(script[k]), static_cast<std::uint32_t>(k));
    inserter.upload(frags);
    const auto t0 = std::chrono::steady_clock::now();
    const hb::gl::FrameReport r = gpu.frame([&] { inserter.dispatch(); }, [&] { return std::uint64_t{frags.size()}; });
    out[k].ms = ms_since(t0);
    for (const hb::gl::FrameReport& done : r.completed) take(done);
    if (r.complete) take(r);
  }
  for (const hb::gl::FrameReport& done : gpu.finish_reports()) take(done);
  return out;
}

struct Scenario {
  const char* name;
  std::vector<int> script;
  std::size_t jump;  // the frame where the depth complexity changes
};

void report(const char* mode, const Scenario& s, const std::vector<FrameFigures>& f) {
  std::uint64_t lossy = 0, lost = 0;
  for (std::size_t k = s.jump; k < f.size(); ++k) {
    lossy += f[k].lost > 0;
    lost += f[k].lost;
  }
  // A normal frame: the last three of the new depth complexity.
  double normal = 0;
  for (std::size_t k = f.size() - 3; k < f.size(); ++k) normal += f[k].ms / 3.0;
  // Frames after the change until the capacity is within 1 % of the last frame's (memory back, or grown).
  std::size_t settle = 0;
  for (std::size_t k = s.jump; k < f.size(); ++k)
    if (static_cast<double>(f[k].capacity) > 1.01 * static_cast<double>(f.back().capacity) ||
        static_cast<double>(f[k].capacity) < 0.99 * static_cast<double>(f.back().capacity))
      settle = k - s.jump + 1;
  std::printf("| %s | %s | %llu | %llu | %llu | %.1f | %.1f | %.1fx | %zu |\n", s.name, mode,
              static_cast<unsigned long long>(lossy), static_cast<unsigned long long>(lost),
              static_cast<unsigned long long>(f[s.jump].gathers), f[s.jump].ms, normal, f[s.jump].ms / normal, settle);
}

}  // namespace

int main(int argc, char** argv) {
  std::uint32_t side = 64;
  int repeats = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--size") side = static_cast<std::uint32_t>(std::atoi(argv[i + 1]));
    else if (a == "--repeats") repeats = std::atoi(argv[i + 1]);
    else if (a == "--late-rounds") g_late_rounds = static_cast<std::uint32_t>(std::atoi(argv[i + 1]));
    else {
      std::fprintf(stderr, "habuffer_adaptive_jumps: unknown option %s (--size N, --repeats R, --late-rounds N)\n",
                   a.c_str());
      return 2;
    }
  }
  if (side == 0 || side > 1024 || repeats < 1) {
    std::fprintf(stderr, "habuffer_adaptive_jumps: --size must be in [1, 1024] and --repeats at least 1\n");
    return 2;
  }
  const hb::Extent screen{side, side};
  hb::gl::EglContext context;
  const std::vector<Scenario> scenarios{
      {"0 -> 40", {0, 40, 40, 40, 40, 40, 40}, 1},
      {"1 -> 40", {1, 1, 40, 40, 40, 40, 40, 40}, 2},
      {"40 -> 1", {40, 40, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1}, 2},
  };
  std::printf("screen %ux%u, %s, automatic table; medians of %d runs per row (frame times)\n\n", side, side,
              hb::gl::to_string(mode()).c_str(), repeats);
  std::printf("| scenario | readback | frames lossy | fragments lost | gathers at the change | change frame ms | "
              "normal frame ms | ratio | frames to settle |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const Scenario& s : scenarios) {
    const std::vector<bool> modes{false, true};
    for (const bool deferred : modes) {
      std::vector<std::vector<FrameFigures>> runs;
      for (int r = 0; r < repeats; ++r) runs.push_back(run(screen, s.script, deferred));
      std::vector<FrameFigures> median = runs.front();
      for (std::size_t k = 0; k < median.size(); ++k) {
        std::vector<double> t;
        for (const auto& r : runs) t.push_back(r[k].ms);
        std::sort(t.begin(), t.end());
        median[k].ms = t[t.size() / 2];
      }
      report(deferred ? "deferred" : "immediate (default)", s, median);
    }
  }
  // A steady frame in each mode, interleaved: 8 layers, 12 frames, the
  // first two left out (counting, shader warm-up).
  std::printf("\n| steady frame (8 layers) | immediate ms | deferred ms |\n|---|---|---|\n");
  const std::vector<int> steady(12, 8);
  std::vector<double> imm, def;
  for (int r = 0; r < repeats; ++r) {
    for (const bool deferred : {false, true}) {
      const std::vector<FrameFigures> f = run(screen, steady, deferred);
      double m = 0;
      for (std::size_t k = 2; k < f.size(); ++k) m += f[k].ms / static_cast<double>(f.size() - 2);
      (deferred ? def : imm).push_back(m);
    }
  }
  std::sort(imm.begin(), imm.end());
  std::sort(def.begin(), def.end());
  std::printf("| median of %d | %.2f | %s |\n", repeats, imm[imm.size() / 2],
              def.empty() ? "-" : std::to_string(def[def.size() / 2]).c_str());
  return 0;
}
