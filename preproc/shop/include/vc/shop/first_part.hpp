// What a measured part says about the program that made it (the first step of self-tuning,
// seeds/000 ch. I fig. 1.12: part i machined with program Pi, its deviations Ri measured).
//
// Each report point is matched to the cuts of Pi that shaped it (on the path the machine
// model predicts for Pi). A point on no cut surface (an edge, a face the program does not
// cut) is left out with the reason; a report with too few points left, or whose points miss
// for a reason that concerns all of them (nothing cut, no tool diameter, the unit), does not
// belong to the program and is refused.
// Then what the tables should not absorb is separated (seeds/000 ch. V, section 5.6): the
// deviations are low-pass filtered over the points of each face (waves shorter than the
// cut-off: vibration marks), and points that differ from their neighbours on the face far
// more than the others do (dwell marks, chips, probing errors) are flagged as outliers and
// left out. Noise is averaged by the strategies (the local radius, the least squares).
#pragma once

#include <cstddef>
#include <istream>
#include <string>
#include <vector>

#include "vc/shop/cmm.hpp"
#include "vc/shop/machined_surface.hpp"
#include "vc/shop/tool_path.hpp"

namespace vc::shop {

struct FirstPartOptions {
  SimulationOptions simulation;  // how the program ran (world, module compensation, tools)
  SurfaceOptions surface;
  double cutoff_mm = 10.0;            // wavelengths shorter than this are not tuned
  double outlier_reach_mm = 25.0;     // a point is compared with its face's points within this
  double outlier_sigmas = 4.0;        // ... and is an outlier beyond this many robust sigmas
  double outlier_floor_mm = 0.003;    // ... and beyond this (noise alone is never an outlier)
  double largest_deviation_mm = 1.0;  // a larger deviation means a wrong unit, not a machine
  // Points on no cut surface are left out; fewer matched than this share of the report, or
  // than this count, and the report is refused (it does not belong to the program).
  double minimum_matched_share = 0.8;
  std::size_t minimum_points = 10;
};

struct LeftOutPoint {
  CmmPoint point;
  std::string reason;  // why it lies on no cut surface
};

struct MatchedPoint {
  CmmPoint point;
  std::vector<Contact> cuts;   // path segments that shaped the surface there, deepest first
  double predicted_mm = 0.0;   // deviation the model predicts for the program
  double filtered_mm = 0.0;    // measured deviation, low-pass over its face
  double short_wave_mm = 0.0;  // measured - filtered
  bool outlier = false;
};

struct FirstPart {
  ToolPath path;  // the program's path as the model predicts it
  std::vector<MatchedPoint> points;
  std::vector<LeftOutPoint> left_out;  // on no cut surface (edges, uncut faces), with the reason
  int outliers = 0;
  double short_wave_rms_mm = 0.0;  // of the points kept
  double robust_sigma_mm = 0.0;    // of the points' differences from their neighbours
};

// Throws std::runtime_error (naming points and their report lines) for a report that does
// not fit the program.
FirstPart analyse_first_part(const machine::Model& model, std::istream& program, const interpreter::Setup& setup,
                             const std::vector<CmmPoint>& report, const FirstPartOptions& options);

// Largest |deviation| and RMS of a set of points (form error figures), measured values.
struct FormError {
  double largest_mm = 0.0, rms_mm = 0.0;
};
FormError form_error(const std::vector<CmmPoint>& points);

}  // namespace vc::shop
