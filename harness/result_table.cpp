#include "habuffer/harness/result_table.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <utility>

#include "habuffer/csv.h"
#include "habuffer/json_writer.h"

namespace habuffer::harness {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

void json_cell(JsonWriter& json, const Cell& c) {
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          json.value(std::nan(""));  // null
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          if (v < 0)
            json.value(static_cast<double>(v));
          else
            json.value(static_cast<std::uint64_t>(v));
        } else if constexpr (std::is_same_v<T, std::vector<std::uint64_t>>) {
          json.begin_array();
          for (const std::uint64_t x : v) json.value(x);
          json.end_array();
        } else {
          json.value(v);
        }
      },
      c);
}

// CSV text of a cell: reals with 9 significant digits, histograms as
// space-separated counts, text quoted when it holds a comma or a quote.
std::string csv_cell(const Cell& c) {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return "";
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          return std::to_string(v);
        } else if constexpr (std::is_same_v<T, double>) {
          if (!std::isfinite(v)) return std::isnan(v) ? "" : (v > 0 ? "inf" : "-inf");
          char buf[32];
          std::snprintf(buf, sizeof buf, "%.9g", v);
          return buf;
        } else if constexpr (std::is_same_v<T, bool>) {
          return v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::vector<std::uint64_t>>) {
          std::string s;
          for (const std::uint64_t x : v) {
            if (!s.empty()) s.push_back(' ');
            s.append(std::to_string(x));
          }
          return s;
        } else {
          if (v.find_first_of(",\"\n") == std::string::npos) return v;
          std::string q;
          q.reserve(v.size() + 8);
          q.push_back('"');
          for (const char ch : v) {
            if (ch == '"') q.push_back('"');
            q.push_back(ch);
          }
          q.push_back('"');
          return q;
        }
      },
      c);
}

void write_json(const ResultTable& t, const std::string& path) {
  JsonWriter json;
  json.begin_object().field("title", t.title);
  json.key("provenance").begin_object().field("command", t.provenance.command).field("machine", t.provenance.machine)
      .field("renderer", t.provenance.renderer).end_object();
  json.key("notes").begin_object();
  for (const auto& [k, v] : t.notes) json.field(k, v);
  json.end_object();
  json.key("rows").begin_array();
  for (const ResultRow& r : t.rows) {
    json.begin_object();
    for (const auto& [k, v] : r.cells()) {
      json.key(k);
      json_cell(json, v);
    }
    json.end_object();
  }
  json.end_array().end_object();
  json.save(path);
}

void write_csv(const ResultTable& t, const std::string& path) {
  const std::vector<std::string> columns = t.columns();
  CsvWriter csv(path);
  for (std::size_t i = 0; i < columns.size(); ++i) (i ? csv.comma() : csv).text(columns[i]);
  csv.endl();
  for (const ResultRow& r : t.rows) {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (i) csv.comma();
      if (const Cell* c = r.find(columns[i])) csv.text(csv_cell(*c));
    }
    csv.endl();
  }
  csv.close();
}

}  // namespace

ResultRow& ResultRow::put(const std::string& column, Cell value) {
  for (auto& [k, v] : cells_)
    if (k == column) {
      v = std::move(value);
      return *this;
    }
  cells_.emplace_back(column, std::move(value));
  return *this;
}

const Cell* ResultRow::find(const std::string& column) const {
  for (const auto& [k, v] : cells_)
    if (k == column) return &v;
  return nullptr;
}

double ResultRow::number(const std::string& column) const {
  const Cell* c = find(column);
  if (c != nullptr) {
    if (const auto* i = std::get_if<std::int64_t>(c)) return static_cast<double>(*i);
    if (const auto* d = std::get_if<double>(c)) return *d;
  }
  throw std::out_of_range("result row has no number in column '" + column + "'");
}

namespace {


}  // namespace

void set_counters(ResultRow& row, const Counters& c) {
  row.set("fragments", c.fragments).set("stored", c.stored());
  // The counters' own columns (counters.h) for writing and reading back
  // alike; `stored` and `failures`, derived, stand before and after them.
  for (const CounterField& f : kCounterFields) row.set(std::string(f.name), c.*f.member);
  row.set("failures", c.failures());
}

std::optional<Counters> counters_of(const ResultRow& row) {
  if (row.find("fragments") == nullptr || row.find("failures") == nullptr) return std::nullopt;
  Counters c;
  c.fragments = static_cast<std::uint64_t>(row.number("fragments"));
  for (const CounterField& f : kCounterFields) c.*f.member = static_cast<std::uint64_t>(row.number(std::string(f.name)));
  return c;
}

std::vector<std::string> ResultTable::columns() const {
  std::vector<std::string> out;
  for (const ResultRow& r : rows)
    for (const auto& [k, v] : r.cells())
      if (std::find(out.begin(), out.end(), k) == out.end()) out.push_back(k);
  return out;
}

void check_table_paths(const std::vector<std::string>& paths) {
  if (paths.empty()) throw std::invalid_argument("no output file given (--out F.json, F.csv or both, comma-separated)");
  for (const std::string& p : paths)
    if (!ends_with(p, ".json") && !ends_with(p, ".csv"))
      throw std::invalid_argument("output '" + p + "' must end in .json or .csv");
}

void write_table(const ResultTable& table, const std::vector<std::string>& paths) {
  check_table_paths(paths);
  for (const std::string& p : paths) (ends_with(p, ".csv") ? write_csv : write_json)(table, p);
}

std::string machine_description() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) model = line.substr(line.find_first_not_of(' ', colon + 1));
      break;
    }
  return model + " x " + std::to_string(std::thread::hardware_concurrency()) + " cores";
}

}  // namespace habuffer::harness
