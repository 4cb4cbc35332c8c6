#include "habuffer/harness/frontier.h"

#include <cmath>
#include <limits>
#include <map>

namespace habuffer::harness {
namespace {

std::string text(const ResultRow& r, const std::string& column) {
  const Cell* c = r.find(column);
  const auto* s = c ? std::get_if<std::string>(c) : nullptr;
  return s ? *s : std::string();
}

std::string group_of(const ResultRow& r) { return text(r, "scene") + "|" + text(r, "size") + "|" + text(r, "path"); }

// PSNR with identical images (infinite) kept above every finite value.
double psnr_of(const ResultRow& r) {
  const double p = r.number("psnr");
  return std::isnan(p) ? std::numeric_limits<double>::infinity() : p;
}

bool dominated(const ResultRow& a, const std::vector<const ResultRow*>& group, const std::string& cost) {
  const double ca = a.number(cost), pa = psnr_of(a);
  for (const ResultRow* b : group) {
    if (b == &a) continue;
    const double cb = b->number(cost), pb = psnr_of(*b);
    if (cb <= ca && pb >= pa && (cb < ca || pb > pa)) return true;
  }
  return false;
}

}  // namespace

std::vector<TechniqueSpec> frontier_techniques(RenderPath path) {
  std::vector<std::string> words{"ha",           "ha:cull=0.9",  "ha:cull=0.99", "ha:cull=0.999", "ha:age=6",
                                 "ha:load=0.5",  "ha:load=0.9",  "lists",        "sorted-lists",  "sorted-lists:cull=0.9",
                                 "sorted-lists:cull=0.99",       "arrays:k=4",   "arrays:k=8",    "arrays:k=16",
                                 "kbuffer:k=1",  "kbuffer:k=2",  "kbuffer:k=4",  "kbuffer:k=8",   "kbuffer:k=16",
                                 "kbuffer:k=4:occ",              "kbuffer:k=8:occ"};
  if (path == RenderPath::Cpu) {
    words.emplace_back("wboit");
    words.emplace_back("blend");
  }
  std::vector<TechniqueSpec> out;
  for (const std::string& w : words) out.push_back(parse_technique_spec(w));
  return out;
}

void mark_pareto(ResultTable& bench) {
  std::map<std::string, std::vector<const ResultRow*>> groups;
  for (const ResultRow& r : bench.rows) groups[group_of(r)].push_back(&r);
  std::vector<std::pair<bool, bool>> marks;
  for (const ResultRow& r : bench.rows) {
    const auto& g = groups[group_of(r)];
    marks.emplace_back(!dominated(r, g, "total_ms"), !dominated(r, g, "memory_bytes"));
  }
  for (std::size_t i = 0; i < bench.rows.size(); ++i)
    bench.rows[i].set("pareto_time", marks[i].first).set("pareto_memory", marks[i].second);
  bench.notes["pareto"] = "pareto_time: no row of the same scene and size is as fast and as accurate and better in one; "
                          "pareto_memory: the same with memory_bytes";
}

ResultTable frontier_picks(const ResultTable& bench, const std::vector<double>& thresholds_db) {
  std::map<std::string, std::vector<const ResultRow*>> groups;
  for (const ResultRow& r : bench.rows) groups[group_of(r)].push_back(&r);
  ResultTable out;
  out.title = "frontier_picks";
  out.provenance = bench.provenance;
  for (const auto& [key, rows] : groups)
    for (const double t : thresholds_db) {
      const ResultRow* best = nullptr;
      for (const ResultRow* r : rows)
        if (psnr_of(*r) >= t && (!best || r->number("total_ms") < best->number("total_ms"))) best = r;
      ResultRow row;
      row.set("scene", text(*rows.front(), "scene")).set("size", text(*rows.front(), "size")).set("target_psnr", t);
      if (best)
        row.set("technique", text(*best, "technique")).set("total_ms", best->number("total_ms"))
            .set("memory_bytes", static_cast<std::uint64_t>(best->number("memory_bytes"))).set("psnr", best->number("psnr"));
      out.rows.push_back(row);
    }
  out.notes["pick"] = "the fastest configuration (total_ms) whose psnr reaches target_psnr; none when no row does";
  return out;
}

}  // namespace habuffer::harness
