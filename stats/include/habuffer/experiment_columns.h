/// @file
/// The columns of the statistics experiments' rows, listed once: name, how
/// the CSV prints it, and how to read it from a row. `habuffer stats` writes
/// its JSON and CSV from these lists and the Python module its dicts of
/// arrays, so a field added to a row is added to every output at one place.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "habuffer/age_experiment.h"
#include "habuffer/key_experiment.h"

namespace habuffer {

/// One cell: text, a real or a count.
using ColumnValue = std::variant<std::string, double, std::uint64_t>;

/// One column of a row type `Row`.
template <class Row>
struct RowColumn {
  std::string_view name;  ///< the JSON key, CSV header and Python dict key
  /// The CSV's printf format of a real ("%.6f"); "" for text and counts
  /// (printed whole); nullptr: the column is not in the CSV (JSON and
  /// Python only), as the CSV was first written.
  const char* csv_format;
  ColumnValue (*get)(const Row& row);  ///< the row's value
};

/// run_age_experiment's rows' columns, in output order.
std::span<const RowColumn<ExperimentRow>> experiment_columns();
/// run_key_experiment's rows' columns, in output order.
std::span<const RowColumn<spatial::KeyExperimentRow>> key_experiment_columns();

/// `value` as the CSV prints it with `format` (see RowColumn::csv_format).
std::string csv_cell(const ColumnValue& value, const char* format);

}  // namespace habuffer
