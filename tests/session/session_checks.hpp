// The claims every compensated headless session makes, over a trace checked against the core
// (vc/trace/session_trace.hpp): shared by the session tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <iostream>
#include <string>
#include <vector>

#include "vc/trace/session_trace.hpp"

namespace vc::test {

struct Extremes {
  double tip_mm = 0, mismatch = 0, pose_mm = 0, pose_rad = 0, pose_mm_faded = 0;
  std::size_t full = 0;
};

inline Extremes extremes(const trace::TraceSummary& s) {
  Extremes e;
  for (const trace::SampleCheck& c : s.samples) {
    e.tip_mm = std::max(e.tip_mm, c.tip_error_mm.norm());
    e.mismatch = std::max(e.mismatch, c.module_mismatch);
    if (c.full_correction) {
      ++e.full;
      e.pose_mm = std::max(e.pose_mm, c.command_pose_mm);
      e.pose_rad = std::max(e.pose_rad, c.command_pose_rad);
    }
  }
  return e;
}

// Column `name` of a trace CSV (std::stod: a sensor's "nan" included).
inline std::vector<double> trace_column(const std::filesystem::path& path, const std::string& name) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream h(line);
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  const auto at = std::find(header.begin(), header.end(), name);
  if (at == header.end()) throw std::runtime_error("no column " + name + " in " + path.string());
  const std::size_t column = static_cast<std::size_t>(at - header.begin());
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string cell;
    for (std::size_t c = 0; c <= column; ++c) std::getline(s, cell, ',');
    values.push_back(std::stod(cell));
  }
  return values;
}

// The claims of a compensated session, at every sample.
inline void expect_compensated(const trace::TraceSummary& s, int model_rotaries, const std::string& what) {
  ASSERT_GT(s.samples.size(), 10000u) << what;
  const Extremes e = extremes(s);
  EXPECT_LT(e.mismatch, 1e-9) << what << ": the module's joints differ from the core's";
  EXPECT_LT(e.pose_mm, 1e-6) << what;
  EXPECT_LT(e.pose_rad, 1e-8) << what;
  if (model_rotaries == 2) {
    EXPECT_GT(e.full, s.samples.size() / 3) << what << ": too few samples with the full correction";
  }
  double direction_where_full = 0;  // `volcomp trace` prints it: the tool direction where it is corrected
  for (const trace::SampleCheck& c : s.samples) {
    if (!c.full_correction) {
      ASSERT_LT(c.command_pose_mm, 1e-6) << what << " sample " << c.sample;
    } else {
      direction_where_full = std::max(direction_where_full, c.direction_error_rad);
    }
  }
  EXPECT_LT(direction_where_full, 1e-6) << what << ": the tool direction where it is corrected";
  // What remains at the tool is LinuxCNC's joint smoothing of a corrected path (~1e-5 mm).
  EXPECT_LT(e.tip_mm, 1e-4) << what;
  std::cout << what << ": module-core max " << e.mismatch << ", commanded pose residual max " << e.pose_mm << " mm / "
            << e.pose_rad << " rad, tool tip after LinuxCNC's interpolation max " << e.tip_mm * 1e3 << " um\n";
}

}  // namespace vc::test
