/// @file
/// Line-oriented CSV reading and fast CSV writing for the interchange files of
/// SPEC 10. Every reading error names the file, the line and the field, so a
/// bad row in a million-line file can be found.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "habuffer/data_error.h"  // DataError, which every reading error is

namespace habuffer {

class AtomicFile;

/// Reads line by line (files of any length, pipes included), with lines of at
/// most kMaxLineBytes; a UTF-8 byte-order mark before the header is skipped.
/// Quoted text in errors is cut short and escaped (habuffer/printable.h).
class CsvReader {
 public:
  static constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;  ///< 1 MiB: longer lines throw DataError

  /// Opens the file; throws DataError if it is missing, a directory, a device
  /// or cannot be opened.
  explicit CsvReader(std::string path);
  /// Reads `text` as if it were the file `name` (tests and fuzzers).
  static CsvReader from_text(std::string name, std::string text);
  /// Closes the file.
  ~CsvReader();
  /// Takes over `other`'s file and position.
  CsvReader(CsvReader&& other) noexcept;
  CsvReader& operator=(CsvReader&&) = delete;
  CsvReader(const CsvReader&) = delete;
  CsvReader& operator=(const CsvReader&) = delete;

  /// Checks the first line equals `header` (fields separated by commas,
  /// surrounding spaces ignored); throws DataError naming both otherwise.
  void expect_header(const std::vector<std::string_view>& header);
  /// The same for a file that may have any of `headers`: returns the index of
  /// the one found; throws DataError naming the header found and every one
  /// accepted. The header is read from the file like any line (a pipe is
  /// read once).
  std::size_t expect_header_among(const std::vector<std::vector<std::string_view>>& headers);
  /// Next non-empty data line split into fields; false at end of file. Throws
  /// DataError when the line has a different number of fields than the header.
  bool next(std::vector<std::string_view>& fields);

  /// The 1-based number of the last line read (0 before the first).
  [[nodiscard]] std::uint64_t line() const { return line_; }
  /// The file's name as given (in every message).
  [[nodiscard]] const std::string& path() const { return path_; }

  /// Field parsers: throw DataError "FILE:LINE: field NAME: ..." on bad text.
  /// A decimal unsigned 32-bit integer.
  [[nodiscard]] std::uint32_t u32(std::string_view text, std::string_view field) const;
  /// Decimal or 0x-prefixed hexadecimal unsigned 32-bit integer.
  [[nodiscard]] std::uint32_t u32_dec_or_hex(std::string_view text, std::string_view field) const;
  /// A decimal float rounded once to float32 (nan and inf are accepted: they
  /// are data the hash counts as invalid, not syntax errors).
  [[nodiscard]] float f32(std::string_view text, std::string_view field) const;
  /// Throws DataError "FILE:LINE: field FIELD: WHAT" (for checks beyond the parsers).
  [[noreturn]] void fail(std::string_view field, const std::string& what) const;

 private:
  CsvReader() = default;
  bool next_line(std::string_view& line);
  // The next raw line (without its newline), refilling the buffer from the file.
  bool read_line(std::string_view& line);
  [[noreturn]] void line_too_long() const;
  std::string path_;
  std::FILE* file_ = nullptr;  // null: text_ holds the whole input
  std::string text_;
  std::size_t pos_ = 0;
  std::uint64_t line_ = 0;
  std::size_t columns_ = 0;
};

/// Buffered writer with integer formatting through std::to_chars. The file
/// appears whole at close() or not at all (habuffer/atomic_file.h): a writer
/// destroyed before close(), or a write error, leaves an earlier file of
/// that name as it was.
class CsvWriter {
 public:
  /// Throws DataError if the file cannot be created.
  explicit CsvWriter(const std::string& path);
  /// Without close(), discards what was written (an earlier file stays).
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  /// Appends `s` as is (no quoting); each appender returns *this to chain.
  CsvWriter& text(std::string_view s);
  /// Appends `v` in decimal.
  CsvWriter& u64(std::uint64_t v);
  CsvWriter& hex(std::uint64_t v, int digits);  ///< 0x + zero-padded lowercase
  CsvWriter& comma() { return text(","); }  ///< a field separator
  CsvWriter& endl() { return text("\n"); }  ///< ends the row ("\n")
  /// Flushes and replaces the target; throws DataError on a write error.
  void close();

 private:
  void flush();
  std::unique_ptr<AtomicFile> file_;
  std::string buffer_;
};

}  // namespace habuffer
