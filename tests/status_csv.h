#pragma once
// The rows of a run's status file (vio_status.csv, lidar_status.csv; docs/formats.md): the stamp and every cell.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/time.h"

namespace vilslam::test {

struct StatusRow {
  TimeNs t_ns = 0;                 // the first cell
  std::vector<std::string> cells;  // all cells, the stamp included (cells[1]: the status)
};

inline std::vector<StatusRow> read_status_rows(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // header
  std::vector<StatusRow> rows;
  while (std::getline(in, line)) {
    StatusRow row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.cells.push_back(cell);
    row.t_ns = std::stoll(row.cells.at(0));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace vilslam::test
