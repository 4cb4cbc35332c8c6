#include "habuffer/csv.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>

#include "habuffer/atomic_file.h"
#include "habuffer/file_roles.h"
#include "habuffer/printable.h"

namespace habuffer {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

void split(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  for (;;) {
    const auto comma = line.find(',');
    fields.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return;
    line.remove_prefix(comma + 1);
  }
}

constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
constexpr std::size_t kReadChunk = std::size_t{1} << 20;

// from_chars<float> reports both overflow and underflow as out of range.
// Underflow rounds to a signed zero (a valid depth 0), overflow to a signed
// infinity (an invalid depth), as strtof would round them.
float out_of_float_range(std::string_view text) {
  const bool negative = text.front() == '-';
  double d = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), d);
  bool tiny = false;
  if (ec == std::errc()) {
    tiny = std::fabs(d) < 1.0;
  } else {
    const auto e = text.find_first_of("eE");
    tiny = e != std::string_view::npos && e + 1 < text.size() && text[e + 1] == '-';
  }
  if (tiny) return negative ? -0.0f : 0.0f;
  return negative ? -INFINITY : INFINITY;
}

}  // namespace

CsvReader::CsvReader(std::string path) : path_(std::move(path)) {
  check_input_file(path_, "CSV file");
  file_ = std::fopen(path_.c_str(), "rb");
  if (file_ == nullptr) throw DataError(printable(path_) + ": cannot open for reading: " + std::strerror(errno));
}

CsvReader CsvReader::from_text(std::string name, std::string text) {
  CsvReader r;
  r.path_ = std::move(name);
  r.text_ = std::move(text);
  return r;
}

CsvReader::~CsvReader() {
  if (file_ != nullptr) std::fclose(file_);
}

CsvReader::CsvReader(CsvReader&& o) noexcept
    : path_(std::move(o.path_)),
      file_(std::exchange(o.file_, nullptr)),
      text_(std::move(o.text_)),
      pos_(o.pos_),
      line_(o.line_),
      columns_(o.columns_) {}

void CsvReader::line_too_long() const {
  throw DataError(printable(path_) + ":" + std::to_string(line_ + 1) + ": line longer than " +
                  std::to_string(kMaxLineBytes) + " bytes (binary data, or not a CSV file?)");
}

bool CsvReader::read_line(std::string_view& line) {
  for (;;) {
    const auto end = text_.find('\n', pos_);
    if (end != std::string::npos) {
      if (end - pos_ > kMaxLineBytes) line_too_long();
      line = std::string_view(text_).substr(pos_, end - pos_);
      pos_ = end + 1;
      return true;
    }
    if (text_.size() - pos_ > kMaxLineBytes) line_too_long();
    std::size_t got = 0;
    if (file_ != nullptr) {
      text_.erase(0, pos_);  // views handed out before this call are no longer used
      pos_ = 0;
      const std::size_t old = text_.size();
      text_.resize(old + kReadChunk);
      got = std::fread(text_.data() + old, 1, kReadChunk, file_);
      text_.resize(old + got);
      if (got == 0 && std::ferror(file_))
        throw DataError(printable(path_) + ": read failed: " + std::strerror(errno));
    }
    if (got == 0) {
      if (pos_ >= text_.size()) return false;
      line = std::string_view(text_).substr(pos_);  // a last line without newline
      pos_ = text_.size();
      return true;
    }
  }
}

bool CsvReader::next_line(std::string_view& line) {
  std::string_view raw;
  while (read_line(raw)) {
    ++line_;
    if (line_ == 1 && raw.substr(0, kUtf8Bom.size()) == kUtf8Bom) raw.remove_prefix(kUtf8Bom.size());
    line = trim(raw);
    if (!line.empty()) return true;
  }
  return false;
}

void CsvReader::expect_header(const std::vector<std::string_view>& header) {
  std::string want;
  for (auto h : header) {
    if (!want.empty()) want.push_back(',');
    want.append(h);
  }
  std::string_view line;
  if (!next_line(line)) throw DataError(printable(path_) + ": empty file, expected header '" + want + "'");
  std::vector<std::string_view> fields;
  split(line, fields);
  if (fields != header)
    throw DataError(printable(path_) + ":" + std::to_string(line_) + ": header is " + excerpt(line, 80) +
                    ", expected '" + want + "'");
  columns_ = header.size();
}

std::size_t CsvReader::expect_header_among(const std::vector<std::vector<std::string_view>>& headers) {
  if (headers.size() == 1) {
    expect_header(headers.front());
    return 0;
  }
  std::string want;
  for (std::size_t i = 0; i < headers.size(); ++i) {
    want += i == 0 ? "'" : i + 1 == headers.size() ? " or '" : ", '";
    for (std::size_t j = 0; j < headers[i].size(); ++j) want.append(j ? "," : "").append(headers[i][j]);
    want += "'";
  }
  std::string_view line;
  if (!next_line(line)) throw DataError(printable(path_) + ": empty file, expected header " + want);
  std::vector<std::string_view> fields;
  split(line, fields);
  for (std::size_t i = 0; i < headers.size(); ++i)
    if (fields == headers[i]) {
      columns_ = headers[i].size();
      return i;
    }
  throw DataError(printable(path_) + ":" + std::to_string(line_) + ": header is " + excerpt(line, 80) + ", expected " +
                  want);
}

bool CsvReader::next(std::vector<std::string_view>& fields) {
  std::string_view line;
  if (!next_line(line)) return false;
  split(line, fields);
  if (fields.size() != columns_)
    throw DataError(printable(path_) + ":" + std::to_string(line_) + ": " + std::to_string(fields.size()) +
                    " fields, expected " + std::to_string(columns_) + ": " + excerpt(line, 80));
  return true;
}

void CsvReader::fail(std::string_view field, const std::string& what) const {
  throw DataError(printable(path_) + ":" + std::to_string(line_) + ": field " + std::string(field) + ": " + what);
}

std::uint32_t CsvReader::u32(std::string_view text, std::string_view field) const {
  std::uint32_t v = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec == std::errc::invalid_argument || end != text.data() + text.size())
    fail(field, excerpt(text) + " is not an unsigned integer");
  if (ec == std::errc::result_out_of_range) fail(field, excerpt(text) + " does not fit in 32 bits");
  return v;
}

std::uint32_t CsvReader::u32_dec_or_hex(std::string_view text, std::string_view field) const {
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    std::uint32_t v = 0;
    const std::string_view digits = text.substr(2);
    auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v, 16);
    if (ec == std::errc::invalid_argument || end != digits.data() + digits.size())
      fail(field, excerpt(text) + " is not a hexadecimal integer");
    if (ec == std::errc::result_out_of_range) fail(field, excerpt(text) + " does not fit in 32 bits");
    return v;
  }
  return u32(text, field);
}

float CsvReader::f32(std::string_view text, std::string_view field) const {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  float v = 0.0f;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec == std::errc::invalid_argument || end != text.data() + text.size())
    fail(field, excerpt(text) + " is not a number");
  if (ec == std::errc::result_out_of_range) return out_of_float_range(text);
  return v;
}

CsvWriter::CsvWriter(const std::string& path) : file_(std::make_unique<AtomicFile>(path)) {
  buffer_.reserve(1 << 20);
}

CsvWriter::~CsvWriter() = default;

void CsvWriter::flush() {
  file_->write(buffer_);
  buffer_.clear();
}

CsvWriter& CsvWriter::text(std::string_view s) {
  buffer_.append(s);
  if (buffer_.size() >= (1 << 20)) flush();
  return *this;
}

CsvWriter& CsvWriter::u64(std::uint64_t v) {
  char tmp[24];
  auto [end, ec] = std::to_chars(tmp, tmp + sizeof tmp, v);
  (void)ec;
  return text(std::string_view(tmp, static_cast<std::size_t>(end - tmp)));
}

CsvWriter& CsvWriter::hex(std::uint64_t v, int digits) {
  char tmp[24];
  auto [end, ec] = std::to_chars(tmp, tmp + sizeof tmp, v, 16);
  (void)ec;
  const auto n = static_cast<int>(end - tmp);
  text("0x");
  for (int i = n; i < digits; ++i) text("0");
  return text(std::string_view(tmp, static_cast<std::size_t>(n)));
}

void CsvWriter::close() {
  flush();
  file_->commit();
}

}  // namespace habuffer
