// LinuxCNC's own interpreter as the independent reading of a G-code program: `rs274 -g`
// prints the canonical machining calls LinuxCNC makes of it (docs/rs274-facts.md).
// Here they become moves in world coordinates (mm, deg):
//     world = rotate_xy(canonical + G92) + G5x + tool length offset
// Quirks handled: each run gets its own HOME (rs274 truncates $HOME/.tool.mmap), the .var
// file is passed as a copy (rs274 rewrites it), and tool lengths and the linear offsets of
// the .var file are written in inches, because the standalone interpreter's machine units
// are inches (measured: a G54 X of 250 in the .var file becomes SET_G5X_OFFSET 6350 mm).
#pragma once

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "linuxcnc_run.hpp"

namespace vc::test {

struct CanonMove {
  enum Kind { Traverse, Feed, Arc } kind = Feed;
  std::array<double, 6> end{};  // world X Y Z A B C (mm, deg)
  // Arcs: plane axes (first, second, normal as in the interpreter: G17 X Y Z, G18 Z X Y,
  // G19 Y Z X), world center, rotation (> 0 counter-clockwise turns, < 0 clockwise).
  int first = 0, second = 1, normal = 2;
  double center_first = 0, center_second = 0;
  int rotation = 0;
  double tool_length_mm = 0;
};

inline bool rs274_available() { return std::filesystem::exists("/usr/bin/rs274"); }

// Runs rs274 -g on `program` (copied into a fresh run folder `name` with the tool table and
// parameter file, if given) and returns its moves. Fails the test if rs274 reports an error.
inline std::vector<CanonMove> rs274_moves(const std::string& name, const std::filesystem::path& program,
                                          const std::filesystem::path& tool_table_mm = {},
                                          const std::filesystem::path& var_file = {}) {
  namespace fs = std::filesystem;
  const fs::path dir = run_folder(name);
  fs::copy_file(program, dir / "program.ngc");
  std::string args = "rs274 -g program.ngc";
  std::vector<double> tool_lengths_mm;  // to undo the 4-decimal printing of tool lengths
  if (!tool_table_mm.empty()) {
    std::ifstream in(tool_table_mm);
    std::ofstream out(dir / "tools.tbl");
    for (std::string line; std::getline(in, line);) {
      std::string body = line.substr(0, line.find(';')), word, written;
      std::istringstream words(body);
      while (words >> word) {
        if (word[0] == 'Z' || word[0] == 'z') {
          tool_lengths_mm.push_back(std::stod(word.substr(1)));
          std::ostringstream inches;
          inches.precision(17);
          inches << "Z" << std::stod(word.substr(1)) / 25.4;
          word = inches.str();
        }
        written += word + " ";
      }
      out << written << "\n";
    }
    args = "rs274 -t tools.tbl -g program.ngc";
  }
  if (!var_file.empty()) {
    // Linear axes of the G28/G30 homes, G92 and G54..G59.3 offsets: parameter numbers whose
    // last digit (of the group of 20 from 5161) is 1, 2 or 3.
    std::ifstream in(var_file);
    std::ofstream out(dir / "params.var");
    out.precision(17);
    int number;
    double value;
    while (in >> number >> value) {
      const bool linear = number >= 5161 && number <= 5413 && (number - 5160) % 10 >= 1 && (number - 5160) % 10 <= 3;
      out << number << '\t' << (linear ? value / 25.4 : value) << '\n';
    }
    args = "rs274 -v params.var " + args.substr(6);
  }
  const CommandResult r = run_in(dir, args + " > canon.txt", 120);
  if (r.exit_code != 0) throw std::runtime_error("rs274 failed: " + r.out);

  std::vector<CanonMove> moves;
  std::array<double, 6> g5x{}, g92{};
  double rotation_deg = 0, tool_z = 0, units = 1.0;
  int plane = 17;
  std::ifstream canon(dir / "canon.txt");
  auto numbers = [](const std::string& args_text) {
    std::vector<double> v;
    std::string cleaned = args_text;
    for (char& c : cleaned)
      if (c == ',' || c == '(' || c == ')') c = ' ';
    std::istringstream s(cleaned);
    for (std::string t; s >> t;) {
      try {
        v.push_back(std::stod(t));
      } catch (...) {
      }
    }
    return v;
  };
  auto world = [&](std::array<double, 6> p) {
    for (int i = 0; i < 6; ++i) p[i] += g92[i];
    const double a = rotation_deg * M_PI / 180, x = p[0], y = p[1];
    p[0] = std::cos(a) * x - std::sin(a) * y;
    p[1] = std::sin(a) * x + std::cos(a) * y;
    for (int i = 0; i < 6; ++i) p[i] += g5x[i];
    p[2] += tool_z;
    return p;
  };
  for (std::string line; std::getline(canon, line);) {
    const auto open = line.find('(');
    if (open == std::string::npos) continue;
    const std::string call = line.substr(line.rfind(' ', open) + 1, open - line.rfind(' ', open) - 1);
    const std::vector<double> v = numbers(line.substr(open));
    auto length = [&](double x) { return x * units; };
    if (call == "USE_LENGTH_UNITS") {
      units = line.find("INCHES") != std::string::npos ? 25.4 : 1.0;
    } else if (call == "SET_G5X_OFFSET") {
      for (int i = 0; i < 6; ++i) g5x[i] = i < 3 ? length(v[i + 1]) : v[i + 1];
    } else if (call == "SET_G92_OFFSET") {
      for (int i = 0; i < 6; ++i) g92[i] = i < 3 ? length(v[i]) : v[i];
    } else if (call == "SET_XY_ROTATION") {
      rotation_deg = v[0];
    } else if (call == "USE_TOOL_LENGTH_OFFSET") {
      // Printed with 4 decimals in program units (2.5 um in inches): take the table's value.
      tool_z = length(v[2]);
      for (double l : tool_lengths_mm)
        if (std::abs(l - tool_z) < 0.003) tool_z = l;
    } else if (call == "SELECT_PLANE") {
      plane = line.find("XZ") != std::string::npos ? 18 : line.find("YZ") != std::string::npos ? 19 : 17;
    } else if (call == "STRAIGHT_TRAVERSE" || call == "STRAIGHT_FEED") {
      CanonMove m;
      m.kind = call == "STRAIGHT_TRAVERSE" ? CanonMove::Traverse : CanonMove::Feed;
      std::array<double, 6> p{};
      for (int i = 0; i < 6; ++i) p[i] = i < 3 ? length(v[i]) : v[i];
      m.end = world(p);
      m.tool_length_mm = tool_z;
      moves.push_back(m);
    } else if (call == "ARC_FEED") {
      // ARC_FEED(first_end, second_end, first_center, second_center, rotation, axis_end, a, b, c)
      CanonMove m;
      m.kind = CanonMove::Arc;
      if (plane == 17) {
        m.first = 0;
        m.second = 1;
        m.normal = 2;
      } else if (plane == 18) {
        m.first = 2;
        m.second = 0;
        m.normal = 1;
      } else {
        m.first = 1;
        m.second = 2;
        m.normal = 0;
      }
      std::array<double, 6> p{}, c{};
      p[m.first] = length(v[0]);
      p[m.second] = length(v[1]);
      p[m.normal] = length(v[5]);
      for (int i = 3; i < 6; ++i) p[i] = v[static_cast<std::size_t>(i + 3)];
      c = p;
      c[m.first] = length(v[2]);
      c[m.second] = length(v[3]);
      m.end = world(p);
      const auto wc = world(c);
      m.center_first = wc[m.first];
      m.center_second = wc[m.second];
      m.rotation = static_cast<int>(v[4]);
      m.tool_length_mm = tool_z;
      moves.push_back(m);
    }
  }
  return moves;
}

// Points along a canonical move from `start` (world), about every `step_mm` (and 0.05 deg).
inline std::vector<std::array<double, 6>> sample(const CanonMove& m, const std::array<double, 6>& start,
                                                 double step_mm) {
  std::vector<std::array<double, 6>> points;
  double sweep = 0, r0 = 0, t0 = 0, r1 = 0;
  double length = 0;
  for (int i = 0; i < 3; ++i) length += (m.end[i] - start[i]) * (m.end[i] - start[i]);
  length = std::sqrt(length);
  if (m.kind == CanonMove::Arc) {
    const auto f = static_cast<std::size_t>(m.first), g = static_cast<std::size_t>(m.second);
    t0 = std::atan2(start[g] - m.center_second, start[f] - m.center_first);
    const double t1 = std::atan2(m.end[g] - m.center_second, m.end[f] - m.center_first);
    r0 = std::hypot(start[f] - m.center_first, start[g] - m.center_second);
    r1 = std::hypot(m.end[f] - m.center_first, m.end[g] - m.center_second);
    const bool ccw = m.rotation > 0;
    sweep = ccw ? t1 - t0 : t0 - t1;
    while (sweep <= 1e-12) sweep += 2 * M_PI;
    while (sweep > 2 * M_PI) sweep -= 2 * M_PI;
    sweep += 2 * M_PI * (std::abs(m.rotation) - 1);
    if (!ccw) sweep = -sweep;
    length = std::abs(sweep) * std::max(r0, r1) +
             std::abs(m.end[static_cast<std::size_t>(m.normal)] - start[static_cast<std::size_t>(m.normal)]);
  }
  double rotary = 0;
  for (int i = 3; i < 6; ++i) rotary = std::max(rotary, std::abs(m.end[i] - start[i]));
  const int n = std::max(1, static_cast<int>(std::ceil(std::max(length / step_mm, rotary / 0.05))));
  for (int k = 1; k <= n; ++k) {
    const double s = static_cast<double>(k) / n;
    std::array<double, 6> p;
    for (int i = 0; i < 6; ++i) p[i] = start[i] + s * (m.end[i] - start[i]);
    if (m.kind == CanonMove::Arc) {
      const auto f = static_cast<std::size_t>(m.first), g = static_cast<std::size_t>(m.second);
      const double r = r0 + s * (r1 - r0), t = t0 + s * sweep;
      p[f] = m.center_first + r * std::cos(t);
      p[g] = m.center_second + r * std::sin(t);
    }
    points.push_back(p);
  }
  return points;
}

}  // namespace vc::test
