/// @file
/// The rows every harness command writes: named cells (numbers, text, lists
/// of counts, or nothing where a value does not apply), one table per
/// command, written as JSON (with what produced it: command, machine,
/// renderer) and CSV (the same columns, one row per line).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "habuffer/fragment.h"

namespace habuffer::harness {

/// Nothing (JSON null, CSV empty), an integer, a real, text, a boolean or a histogram (counts per bin).
using Cell = std::variant<std::monostate, std::int64_t, double, std::string, bool, std::vector<std::uint64_t>>;

/// One row: named cells in the order first set.
class ResultRow {
 public:
  /// Sets `column` to `value`, replacing the cell when the column is already set; returns *this to chain.
  ResultRow& put(const std::string& column, Cell value);
  /// put with the value converted to its Cell alternative (unsigned and int as std::int64_t, text as std::string).
  ResultRow& set(const std::string& column, std::uint64_t v) { return put(column, static_cast<std::int64_t>(v)); }
  /// See above.
  ResultRow& set(const std::string& column, std::uint32_t v) { return put(column, static_cast<std::int64_t>(v)); }
  /// See above.
  ResultRow& set(const std::string& column, int v) { return put(column, static_cast<std::int64_t>(v)); }
  /// See above.
  ResultRow& set(const std::string& column, double v) { return put(column, v); }
  /// See above.
  ResultRow& set(const std::string& column, bool v) { return put(column, v); }
  /// See above.
  ResultRow& set(const std::string& column, const char* v) { return put(column, std::string(v)); }
  /// See above.
  ResultRow& set(const std::string& column, const std::string& v) { return put(column, v); }
  /// See above.
  ResultRow& set(const std::string& column, const std::vector<std::uint64_t>& v) { return put(column, v); }
  /// The cell of `column`, or nullptr when the row has none (owned by the row).
  [[nodiscard]] const Cell* find(const std::string& column) const;
  /// The cell as a number (integers and reals); throws std::out_of_range naming the column otherwise.
  [[nodiscard]] double number(const std::string& column) const;
  /// Every cell, in the order first set.
  [[nodiscard]] const std::vector<std::pair<std::string, Cell>>& cells() const { return cells_; }

 private:
  std::vector<std::pair<std::string, Cell>> cells_;  // in the order first set
};

/// Every counter of a run as columns (fragments, stored, each reason, failures).
void set_counters(ResultRow& row, const Counters& c);
/// The counters set_counters wrote into `row`, or nothing when it holds none.
std::optional<Counters> counters_of(const ResultRow& row);

/// What produced a table: printed in the JSON and named by every figure.
struct Provenance {
  std::string command;   ///< the command line
  std::string machine;   ///< CPU model and cores
  std::string renderer;  ///< "llvmpipe (...)", "NVIDIA H100 ...", "cpu"
};

/// One command's results (see the file comment).
struct ResultTable {
  std::string title;  ///< "sweep", "bench", "fig2", ...
  Provenance provenance;  ///< what produced it
  std::map<std::string, std::string> notes;  ///< anything else a reader needs (units, model, tolerance)
  std::vector<ResultRow> rows;  ///< in the order produced

  /// Every column in order of first appearance over the rows.
  [[nodiscard]] std::vector<std::string> columns() const;
};

/// Writes `table` to each path by its extension (.json or .csv); throws
/// std::invalid_argument for any other extension, DataError when writing fails.
void write_table(const ResultTable& table, const std::vector<std::string>& paths);
/// Throws std::invalid_argument unless every path ends in .json or .csv.
void check_table_paths(const std::vector<std::string>& paths);

/// "Intel(R) Xeon(R) ... x 2 cores" from /proc/cpuinfo, or "unknown CPU x N cores".
std::string machine_description();

}  // namespace habuffer::harness
