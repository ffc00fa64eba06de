#include "io/csv.h"

#include <cctype>
#include <charconv>
#include <cstdlib>
#include <limits>
#include <cmath>
#include <fstream>

#include "common/error.h"
#include "common/log.h"

namespace vilslam {
namespace {

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return {};
  const auto end = s.find_last_not_of(" \t\r");
  return s.substr(begin, end - begin + 1);
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  if (separator == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      const auto begin = line.find_first_not_of(" \t", i);
      if (begin == std::string::npos) break;
      auto end = line.find_first_of(" \t", begin);
      if (end == std::string::npos) end = line.size();
      fields.push_back(line.substr(begin, end - begin));
      i = end;
    }
    return fields;
  }
  std::size_t begin = 0;
  while (true) {
    const auto end = line.find(separator, begin);
    fields.push_back(trim(line.substr(begin, end == std::string::npos ? std::string::npos : end - begin)));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return fields;
}

}  // namespace

Table::Table(const std::string& path, char separator, std::size_t min_fields) : path_(path) {
  std::ifstream f(path);
  if (!f) throw InputError(path, "cannot open file");
  std::string line;
  long number = 0;
  while (std::getline(f, line)) {
    ++number;
    const std::string content = trim(line);
    if (content.empty() || content[0] == '#') continue;
    TableRow row{number, split(content, separator)};
    if (row.fields.size() < min_fields) {
      throw InputError(path, "truncated row: expected " + std::to_string(min_fields) + " fields, got " +
                                 std::to_string(row.fields.size()), number);
    }
    rows_.push_back(std::move(row));
  }
  if (f.bad()) throw InputError(path, "read error");
}

const std::string& Table::text(const TableRow& row, std::size_t col) const {
  if (col >= row.fields.size()) throw InputError(path_, "missing field " + std::to_string(col + 1), row.line);
  if (row.fields[col].empty()) throw InputError(path_, "empty field " + std::to_string(col + 1), row.line);
  return row.fields[col];
}

TimeNs Table::time_ns(const TableRow& row, std::size_t col) const {
  return parse<TimeNs>(row, col, "an integer timestamp");
}

long Table::integer(const TableRow& row, std::size_t col) const { return parse<long>(row, col, "an integer"); }

double Table::number(const TableRow& row, std::size_t col) const {
  const double v = parse<double>(row, col, "a number");
  if (!std::isfinite(v)) {
    throw InputError(path_, "field " + std::to_string(col + 1) + " is not finite: '" + row.fields[col] + "'", row.line);
  }
  return v;
}

template <typename T>
T Table::parse(const TableRow& row, std::size_t col, const char* what) const {
  const std::string& s = text(row, col);
  T v{};
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) {
    throw InputError(path_, "field " + std::to_string(col + 1) + " is not " + what + ": '" + s + "'", row.line);
  }
  return v;
}

TimeNs Table::seconds_as_ns(const TableRow& row, std::size_t col) const {
  const std::string& s = text(row, col);
  const auto bad = [&](const char* problem) {
    return InputError(path_, "field " + std::to_string(col + 1) + " " + problem + ": '" + s + "'", row.line);
  };
  std::size_t i = 0;
  const bool negative = s[0] == '-';
  if (s[0] == '-' || s[0] == '+') ++i;
  std::string digits;
  long int_digits = 0;
  bool seen_dot = false;
  for (; i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.'); ++i) {
    if (s[i] == '.') {
      if (seen_dot) throw bad("is not a time in seconds");
      seen_dot = true;
    } else {
      digits.push_back(s[i]);
      if (!seen_dot) ++int_digits;
    }
  }
  if (digits.empty()) throw bad("is not a time in seconds");
  if (i < s.size()) {
    int exponent = 0;
    const char* begin = s.data() + i + 1;
    if (begin < s.data() + s.size() && *begin == '+') ++begin;
    const auto [end, ec] = std::from_chars(begin, s.data() + s.size(), exponent);
    if ((s[i] != 'e' && s[i] != 'E') || ec != std::errc() || end != s.data() + s.size() || std::abs(exponent) > 30) {
      throw bad("is not a time in seconds");
    }
    int_digits += exponent;
  }
  const long ns_digits = int_digits + 9;  // digits of the result before the rounding position
  TimeNs ns = 0;
  for (long k = 0; k < ns_digits; ++k) {
    const int d = k < static_cast<long>(digits.size()) ? digits[k] - '0' : 0;
    if (ns > (std::numeric_limits<TimeNs>::max() - d) / 10) throw bad("is out of the time range");
    ns = ns * 10 + d;
  }
  if (ns_digits >= 0 && ns_digits < static_cast<long>(digits.size()) && digits[ns_digits] >= '5') ++ns;
  return negative ? -ns : ns;
}

void Table::require_increasing(const std::vector<TimeNs>& times) const {
  for (std::size_t i = 1; i < times.size(); ++i) {
    if (times[i] <= times[i - 1]) throw_not_after(times, i, i - 1);
  }
}

std::vector<std::size_t> Table::rows_without_repeated_times(const std::vector<TimeNs>& times) const {
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!keep.empty() && times[i] == times[keep.back()]) {
      spdlog::warn("{}:{}: timestamp {} repeats line {}; row dropped", path_, rows_[i].line, times[i],
                   rows_[keep.back()].line);
      continue;
    }
    if (!keep.empty() && times[i] < times[keep.back()]) throw_not_after(times, i, keep.back());
    keep.push_back(i);
  }
  return keep;
}

void Table::throw_not_after(const std::vector<TimeNs>& times, std::size_t i, std::size_t previous) const {
  throw InputError(path_, "timestamp " + std::to_string(times[i]) + " is not after the previous one (" +
                              std::to_string(times[previous]) + ")", rows_[i].line);
}

}  // namespace vilslam
