#pragma once
// Bad input is reported as InputError: the message names the file (and line when there is one).
// The CLI turns it into exit code 2; it is never a crash.
#include <stdexcept>
#include <string>

namespace vilslam {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& problem, long line = 0)
      : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + problem),
        file_(file),
        line_(line) {}
  const std::string& file() const { return file_; }
  long line() const { return line_; }

 private:
  std::string file_;
  long line_;
};

}  // namespace vilslam
