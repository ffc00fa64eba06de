#include "common/publish_dir.h"

#include <fcntl.h>
#include <stdio.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace vilslam {

namespace fs = std::filesystem;

void publish_directory(const std::string& staging, const std::string& target) {
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error("cannot move " + staging + " to " + target + ": " + what);
  };
  std::error_code ec;
  if (!fs::exists(target, ec)) {
    fs::rename(staging, target, ec);
    if (ec) fail(ec.message());
    return;
  }
  if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) == 0) {
    fs::remove_all(staging, ec);  // the previous content; a leftover is removed by the next writer's clean-up
    return;
  }
  if (errno != EINVAL && errno != ENOSYS) fail(std::strerror(errno));
  const std::string aside = target + ".previous";
  fs::remove_all(aside, ec);
  fs::rename(target, aside, ec);
  if (ec) fail("cannot move the previous folder aside: " + ec.message());
  fs::rename(staging, target, ec);
  if (ec) fail(ec.message());
  fs::remove_all(aside, ec);
}

}  // namespace vilslam
