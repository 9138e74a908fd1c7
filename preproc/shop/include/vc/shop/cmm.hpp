// CMM measurement plans and reports (CSV, units in the header), and the virtual CMM that
// measures a machined surface.
//
// Plan:   id,x[mm],y[mm],z[mm],i,j,k                   nominal point, unit normal out of the material
// Report: the plan's columns and deviation[um]        (+ = material left, along the normal)
//         or mx[mm],my[mm],mz[mm]                      the measured point: deviation = n . (m - p)
// Coordinates are in the part frame. Length units: mm, um, nm.
// A report exported by CMM software in another layout is read by read_cmm_export
// (cmm_export.hpp): read_cmm_points takes a file whose header starts with `id` as ours, any
// other as an export.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vc/shop/machined_surface.hpp"

namespace vc::shop {

struct CmmPoint {
  std::string id;
  Eigen::Vector3d nominal = Eigen::Vector3d::Zero();  // part frame, mm
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, out of the material
  std::optional<double> deviation_mm;                 // measured (reports only)
  int line = 0;                                       // in its file, for messages
};

// How to read a CMM software's export where the file does not say it (selftune's options).
enum class DeviationSign {
  Unstated,            // refused when the deviation column is the one used
  ActualMinusNominal,  // (actual - nominal) . normal: with outward normals, + = material left (ours)
  NominalMinusActual,  // the opposite
};
struct ReportFormat {
  std::string unit;  // "mm" or "inch" (any length_unit name): for columns whose header names none
  DeviationSign sign = DeviationSign::Unstated;
  bool decimal_comma = false;  // numbers written 12,5 (a ';' or tab separated file)
  bool any() const { return !unit.empty() || sign != DeviationSign::Unstated || decimal_comma; }
};

// Reads a plan or a report; `report` demands a deviation (or measured point) column. Our CSV
// (header starting with id) states its units and sign itself: `format` must then be empty or
// say actual-minus-nominal. `layout`, if given, receives how the file was read (for the user
// to check: which column is what, the units). Throws vc::LoadError with file:line:column.
std::vector<CmmPoint> read_cmm_points(const std::string& path, bool report, const ReportFormat& format = {},
                                      std::string* layout = nullptr);
void write_cmm_report(std::ostream& out, const std::vector<CmmPoint>& points, const std::vector<std::string>& comments);

struct CmmOptions {
  double noise_um = 0.0;         // standard deviation of the gaussian noise added to each reading
  double probe_radius_mm = 0.0;  // stylus ball: it rests on the highest material under it
  unsigned seed = 1;             // of the noise
};

// Measures every point of `plan` on the surface. Throws std::runtime_error naming the first
// point that lies on no cut surface (no cutting tool came within reach of it).
std::vector<CmmPoint> measure(const MachinedSurface& surface, std::vector<CmmPoint> plan, const CmmOptions& options);

}  // namespace vc::shop
