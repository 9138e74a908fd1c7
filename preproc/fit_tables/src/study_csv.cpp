#include "vc/fit_tables/study_csv.hpp"

#include <cmath>
#include <string>

#include "vc/tables/number_text.hpp"

namespace vc::fit_tables {
namespace {

constexpr double kRadToArcsec = 180.0 * 3600.0 / M_PI;

// Fixed decimals without trailing zeros ("7.1", "-5", "0.000123"): table values to 1e-6 um
// or arcsec, far below any controller's resolution.
std::string value_text(double v) { return without_negative_zero(without_trailing_zeros(fixed_text(v, 6))); }

bool rotary_output(const machine::Model& model, const Table& t) {
  return model.axes[static_cast<std::size_t>(t.output)].type == machine::AxisType::Rotary;
}

std::string lengths(const std::vector<double>& l) {
  std::string s;
  for (double v : l) s += (s.empty() ? "" : ", ") + number_text(v);
  return s.empty() ? "none" : s;
}

}  // namespace

double display_value(const machine::Model& model, const Table& t, double x) {
  if (t.kind == TableKind::Squareness) return std::atan(x) * kRadToArcsec;
  return rotary_output(model, t) ? x * 3600.0 : x * 1e3;
}

const char* display_unit(const machine::Model& model, const Table& t) {
  return t.kind == TableKind::Squareness || rotary_output(model, t) ? "arcsec" : "um";
}

void write_report_csv(const Study& s, const machine::Model& model, const Controller& controller,
                      const StudyOptions& options, std::ostream& out) {
  std::string names;
  for (const Table& t : s.set.tables) names += (names.empty() ? "" : " ") + s.set.name(model, t);
  out << "# volcomp fit-tables: " << model.info.name << " (" << model.path << ") with controller " << controller.name
      << ": " << controller.title << "\n"
      << "# criterion " << (options.fit.criterion == Criterion::Minimax ? "minimax" : "ls") << "; "
      << s.set.tables.size() << " tables (" << names << "), " << s.set.unknowns << " values\n"
      << "# fitted at L = " << lengths(s.fitted_lengths_mm) << " mm on a grid of " << s.levels
      << " positions per joint (" << s.grid_poses << " poses) plus " << s.added_poses
      << " worst fresh poses (refit); judged also at L = " << lengths(s.check_lengths_mm) << " mm (not fitted)\n"
      << "# set grid: the grid's poses at that L; set fresh: " << options.fresh_poses
      << " random poses over the travel at that L, never fitted; set programs: the poses of the part programs "
         "given (--programs) at that L, fitted with the grid\n"
      << "# M = max |tool-tip error|, Delta = max - min |tool-tip error| over the set (seeds/000 sec. 3.3.3), computed "
         "on the "
         "nonlinear model\n"
      << "# none: no compensation; usual: each table its own deviation negated; modified: the fit (the source's "
         "modified "
         "method); full: the full correction (volkins), the bound\n";
  for (const std::string& note : s.set.notes) out << "# note: " << note << "\n";
  out << "tool_length[mm],fitted,set,poses,none_M[um],none_Delta[um],usual_M[um],usual_Delta[um],modified_M[um],"
         "modified_Delta[um],full_M[um],full_Delta[um]\n";
  for (const ReportRow& r : s.rows) {
    out << number_text(r.tool_length_mm) << ',' << (r.fitted_length ? "yes" : "no") << ',' << r.set << ','
        << r.none.poses;
    for (const Figures* f : {&r.none, &r.usual, &r.modified, &r.full})
      out << ',' << fixed_text(f->max_um, 4) << ',' << fixed_text(f->delta_um, 4);
    out << '\n';
  }
}

void write_tables_csv(const Study& s, const machine::Model& model, const Controller& controller, std::ostream& out) {
  out << "# volcomp fit-tables: " << model.info.name << " with controller " << controller.name
      << ": the tables' values, a correction ADDED to the output joint's commanded position\n"
      << "# position: the input joint's position (mm or deg); nodes equally spaced over its travel, linear between, "
         "held outside\n"
      << "# modified: the fit; usual: each table its own deviation negated; values in um (linear joint) or arcsec "
         "(rotary joint, squareness: output += tan(value) x input)\n";
  bool directional = false;
  for (const Table& t : s.set.tables) directional = directional || t.direction_dependent;
  if (directional)
    out << "# direction-dependent tables: both directions take these values (the model has no reversal error)\n";
  out << "table,kind,input,output,node,position,position_unit,modified,usual,value_unit\n";
  for (std::size_t k = 0; k < s.set.tables.size(); ++k) {
    const Table& t = s.set.tables[k];
    const std::string head = std::to_string(k + 1) + ',' + kind_name(t.kind) + ',' +
                             model.axes[static_cast<std::size_t>(t.input)].letter + ',' +
                             model.axes[static_cast<std::size_t>(t.output)].letter + ',';
    const char* unit = display_unit(model, t);
    if (t.kind == TableKind::Squareness) {
      out << head << "0,,-," << value_text(display_value(model, t, s.modified[t.first_unknown])) << ','
          << value_text(display_value(model, t, s.usual[t.first_unknown])) << ',' << unit << '\n';
      continue;
    }
    const bool rotary_input = model.axes[static_cast<std::size_t>(t.input)].type == machine::AxisType::Rotary;
    for (std::size_t n = 0; n < t.nodes.size(); ++n) {
      const int u = t.unknown_of_node(static_cast<int>(n));
      out << head << n << ',' << value_text(t.nodes[n]) << ',' << (rotary_input ? "deg" : "mm") << ','
          << value_text(display_value(model, t, s.modified[u])) << ','
          << value_text(display_value(model, t, s.usual[u])) << ',' << unit << '\n';
    }
  }
}

}  // namespace vc::fit_tables
