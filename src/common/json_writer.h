#pragma once
// A tiny streaming JSON writer (no JSON library is installed): objects, arrays, strings, numbers, bools.
// Commas and indentation are handled; keys are written in the order given, so output is deterministic.
#include <cstdint>
#include <string>
#include <vector>

namespace vilslam {

class JsonWriter {
 public:
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  // Inside an object: the key of the next value (or of the next begin_object/begin_array).
  JsonWriter& key(const std::string& name);
  JsonWriter& value(const std::string& s);
  JsonWriter& value(const char* s) { return value(std::string(s)); }
  JsonWriter& value(double x);  // non-finite numbers are written as null (JSON has no NaN)
  JsonWriter& value(std::int64_t x);
  JsonWriter& value(std::uint64_t x);
  JsonWriter& value(int x) { return value(static_cast<std::int64_t>(x)); }
  JsonWriter& value(bool b);
  JsonWriter& null();

  // The document so far (complete once every begin_* has its end_*), ending with a newline.
  std::string str() const;
  // Writes str() to a temporary file next to path and renames it into place (never half-written).
  // Throws std::runtime_error when the file cannot be written.
  void save(const std::string& path) const;

 private:
  void before_value();
  void newline();
  JsonWriter& close(char bracket);
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

// Writes text to path through a temporary file in the same folder and a rename.
void write_file_atomic(const std::string& path, const std::string& text);

}  // namespace vilslam
