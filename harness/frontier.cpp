#include "habuffer/harness/frontier.h"

#include <algorithm>
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

// A row's place on the axes of one front: costs (smaller is better), then
// psnr (larger is better).
struct Point {
  std::vector<double> costs;
  double psnr = 0.0;
};

Point point_of(const ResultRow& r, const std::vector<std::string>& costs) {
  Point p;
  for (const std::string& c : costs) p.costs.push_back(r.number(c));
  p.psnr = psnr_of(r);
  return p;
}

// b at least as good as a on every axis and strictly better on one.
bool dominates(const Point& b, const Point& a) {
  bool better = b.psnr > a.psnr;
  if (b.psnr < a.psnr) return false;
  for (std::size_t i = 0; i < a.costs.size(); ++i) {
    if (b.costs[i] > a.costs[i]) return false;
    better = better || b.costs[i] < a.costs[i];
  }
  return better;
}

// One mark per row of `rows`: on the front of `costs` and psnr.
std::vector<bool> front(const std::vector<const ResultRow*>& rows, const std::vector<std::string>& costs) {
  std::vector<Point> points;
  for (const ResultRow* r : rows) points.push_back(point_of(*r, costs));
  std::vector<bool> on(points.size(), true);
  for (std::size_t a = 0; a < points.size(); ++a)
    for (std::size_t b = 0; b < points.size() && on[a]; ++b)
      if (b != a && dominates(points[b], points[a])) on[a] = false;
  return on;
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
  for (const std::string& w : words)
    if (TechniqueSpec t = parse_technique_spec(w); runs_on_path(path, t.technique)) out.push_back(t);
  return out;
}

void mark_pareto(ResultTable& bench) {
  std::map<std::string, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < bench.rows.size(); ++i) groups[group_of(bench.rows[i])].push_back(i);
  const std::vector<std::pair<const char*, std::vector<std::string>>> fronts{
      {"pareto_time", {"total_ms"}}, {"pareto_memory", {"memory_bytes"}}, {"pareto_3d", {"total_ms", "memory_bytes"}}};
  for (const auto& [key, members] : groups) {
    std::vector<const ResultRow*> rows;
    for (const std::size_t i : members) rows.push_back(&bench.rows[i]);
    std::vector<std::vector<bool>> marks;
    for (const auto& f : fronts) marks.push_back(front(rows, f.second));
    for (std::size_t m = 0; m < members.size(); ++m)
      for (std::size_t f = 0; f < fronts.size(); ++f) bench.rows[members[m]].set(fronts[f].first, marks[f][m]);
  }
  bench.notes["pareto"] =
      "per scene, size and path, a row is on a front when no other row is at least as good on every axis and better "
      "on one: pareto_time (total_ms, psnr), pareto_memory (memory_bytes, psnr), pareto_3d (total_ms, memory_bytes, "
      "psnr); rows equal on every axis dominate nobody and stay on it together";
}

ResultTable frontier_picks(const ResultTable& bench, const std::vector<double>& thresholds_db,
                           const std::vector<double>& budgets_bytes_per_fragment) {
  std::map<std::string, std::vector<const ResultRow*>> groups;
  for (const ResultRow& r : bench.rows) groups[group_of(r)].push_back(&r);
  ResultTable out;
  out.title = "frontier_picks";
  out.provenance = bench.provenance;
  for (const auto& [key, rows] : groups)
    for (const double t : thresholds_db)
      for (const double budget : budgets_bytes_per_fragment) {
        const ResultRow* best = nullptr;
        for (const ResultRow* r : rows)
          if (psnr_of(*r) >= t && r->number("bytes_per_fragment") <= budget &&
              (!best || r->number("total_ms") < best->number("total_ms")))
            best = r;
        ResultRow row;
        row.set("scene", text(*rows.front(), "scene")).set("size", text(*rows.front(), "size")).set("target_psnr", t)
            .set("memory_budget", budget);
        if (best)
          row.set("technique", text(*best, "technique")).set("total_ms", best->number("total_ms"))
              .set("memory_bytes", static_cast<std::uint64_t>(best->number("memory_bytes")))
              .set("bytes_per_fragment", best->number("bytes_per_fragment")).set("psnr", best->number("psnr"));
        else
          row.set("technique", "none");
        out.rows.push_back(row);
      }
  out.notes["pick"] = "the fastest configuration (total_ms) whose psnr reaches target_psnr and whose bytes_per_fragment "
                      "(memory_bytes / fragments) is within memory_budget; technique none when no row does";
  out.notes["memory_budget"] = "bytes per fragment; inf (null in JSON): no budget";
  return out;
}

}  // namespace habuffer::harness
