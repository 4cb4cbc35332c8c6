// habuffer's CSG beside OpenCSG on the CSG curve, in Google Benchmark form
// (GPL-2+ through OpenCSG: built into habuffer_bench only where OpenCSG is
// found; the library and the CLI never link it). Each render to glFinish
// (manual time); the counter `mismatches` counts pixels whose visible
// primitive differs from the ray caster outside its edge band. The full curve
// with a table: habuffer_csg_peers.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "habuffer/csg.h"
#include "habuffer/harness/csg_figure.h"
#include "habuffer/render/csg_renderer.h"
#include "opencsg_peer.h"

namespace {

using namespace habuffer;

peers::CompatContext& compat() {
  static peers::CompatContext context;  // made once; current only inside each benchmark
  return context;
}

constexpr Extent kSize{128, 128};

// method 0: habuffer's HA-buffer; 1: Goldfeather with occlusion queries; 2: SCS with occlusion queries.
void BM_CsgPeers(benchmark::State& state) {
  const auto method = static_cast<int>(state.range(0));
  const auto n = static_cast<std::uint32_t>(state.range(1));
  const peers::CompatContext::Current current(compat());
  const harness::CsgCylinders c = harness::csg_cylinders(n);
  const CsgExpression e = CsgExpression::parse(c.expression, c.names);
  CsgRenderSettings s;
  s.screen = kSize;
  s.camera = {30.0f, 25.0f, 45.0f};
  CsgRender r = render_csg(c.scene, e, s);  // also the camera the peers use
  std::unique_ptr<peers::OpenCsgPeer> peer;
  std::vector<peers::CsgProduct> products{{{0}, {}}};
  for (std::uint32_t k = 1; k <= n; ++k) products[0].subtracted.push_back(k);
  const peers::OpenCsgMethod m{method == 2 ? peers::OpenCsgAlgorithm::Scs : peers::OpenCsgAlgorithm::Goldfeather, true};
  if (method > 0) {
    peer = std::make_unique<peers::OpenCsgPeer>(c.scene, std::vector<std::uint32_t>(c.scene.meshes.size(), 1), kSize);
    (void)peer->render(products, r.camera, m);  // OpenCSG compiles its programs at the first render
  }
  for (auto _ : state) {
    if (method == 0) {
      r = render_csg(c.scene, e, s);
      state.SetIterationTime((r.gather_ms + r.resolve_ms) / 1000.0);
    } else {
      peers::OpenCsgRender p = peer->render(products, r.camera, m);
      state.SetIterationTime(p.ms / 1000.0);
      r.primitive = std::move(p.primitive);
    }
  }
  state.counters["mismatches"] = static_cast<double>(check_csg(c.scene, e, r, kSize).mismatches);
  state.SetLabel(method == 0 ? "habuffer-ha" : "opencsg-" + m.name());
}
BENCHMARK(BM_CsgPeers)
    ->ArgNames({"method", "cylinders"})
    ->ArgsProduct({{0, 1, 2}, {8, 64, 512}})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace
