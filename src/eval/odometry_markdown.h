#pragma once
// Markdown of the odometry table (eval/odometry_table.h): the table printed by `vilslam odometry-table`
// and the whole page it writes (docs/odometry.md).
#include <string>
#include <vector>

#include "eval/odometry_table.h"

namespace vilslam::eval {

// The table (header, one line per preset) followed by one line per lost run giving the reason.
std::string odometry_table_markdown(const std::vector<OdometryRow>& rows);

struct OdometryDocument {
  std::string command;   // the exact command that made the table
  std::string date_utc;  // e.g. "2026-11-22 15:40 UTC"
  std::string machine;   // e.g. "host x86_64, 2 hardware threads"
  double wall_s = 0;     // time the command took
  std::string note;      // optional text, e.g. the provenance of reused simulations
};

// The whole page: intro, command, definitions, table, the paper's values, date and machine.
std::string odometry_document_markdown(const std::vector<OdometryRow>& rows, const OdometryDocument& doc);

}  // namespace vilslam::eval
