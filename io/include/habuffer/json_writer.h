/// @file
/// A minimal streaming JSON writer (objects, arrays, strings, numbers) for the
/// stats files and result tables; it inserts commas and escapes strings, so
/// callers only say what comes next.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace habuffer {

/// Builds one JSON text in memory; every call returns *this to chain. It does not check that calls nest.
class JsonWriter {
 public:
  JsonWriter& begin_object();  ///< "{"
  JsonWriter& end_object();    ///< "}"
  JsonWriter& begin_array();   ///< "["
  JsonWriter& end_array();     ///< "]"
  JsonWriter& key(std::string_view k);    ///< an object member's name (escaped); its value follows
  JsonWriter& value(std::string_view s);  ///< a string, escaped
  JsonWriter& value(const char* s) { return value(std::string_view(s)); }  ///< a string, escaped
  JsonWriter& value(std::uint64_t v);     ///< an integer
  JsonWriter& value(std::uint32_t v) { return value(std::uint64_t{v}); }  ///< an integer
  JsonWriter& value(double v);  ///< non-finite values become null
  JsonWriter& value(bool v);  ///< true or false
  /// key(k).value(v): one object member.
  template <class T>
  JsonWriter& field(std::string_view k, const T& v) {
    return key(k).value(v);
  }

  /// The text so far.
  [[nodiscard]] const std::string& str() const { return out_; }
  /// Writes str() and a newline to `path`, whole or not at all (AtomicFile); throws DataError on failure.
  void save(const std::string& path) const;

 private:
  void separate();
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

}  // namespace habuffer
