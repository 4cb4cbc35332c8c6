// A minimal streaming JSON writer (objects, arrays, strings, numbers) for the
// stats files; it inserts commas and escapes strings.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace habuffer {

class JsonWriter {
 public:
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(std::string_view k);
  JsonWriter& value(std::string_view s);
  JsonWriter& value(const char* s) { return value(std::string_view(s)); }
  JsonWriter& value(std::uint64_t v);
  JsonWriter& value(std::uint32_t v) { return value(std::uint64_t{v}); }
  JsonWriter& value(double v);  // non-finite values become null
  JsonWriter& value(bool v);
  template <class T>
  JsonWriter& field(std::string_view k, const T& v) {
    return key(k).value(v);
  }

  [[nodiscard]] const std::string& str() const { return out_; }
  // Writes str() and a newline to `path`; throws DataError on failure.
  void save(const std::string& path) const;

 private:
  void separate();
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

}  // namespace habuffer
