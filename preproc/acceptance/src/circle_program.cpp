#include "vc/acceptance/circle_program.hpp"

#include <cmath>
#include <sstream>

#include "vc/tables/number_text.hpp"

namespace vc::acceptance {
namespace {

constexpr double kFeedInRad = 10 * M_PI / 180;

std::string plane_word(const Circle& c) { return c.plane == "XY" ? "G17" : c.plane == "YZ" ? "G19" : "G18"; }

// The arc centre's words: the centre minus the arc's start, on the plane's axes (I J K for X Y Z).
std::string centre_words(const Circle& c, const Eigen::Vector3d& from) {
  std::string words;
  for (int i : {0, 1, 2})
    if (i == c.first() || i == c.second())
      words += std::string(" ") + "IJK"[i] + fixed_text(c.centre_mm[i] - from[i], 6);
  return words;
}

}  // namespace

std::string circle_program(const Plan& plan, const Circle& c, const machine::Model& model) {
  const Eigen::Vector3d offset(0, 0, plan.tool_offset_mm);  // program Z = joint Z - G43.1's offset
  const auto point = [&](double angle_deg) {
    const Eigen::Vector3d p = c.at(angle_deg * M_PI / 180) - offset;
    return "X" + fixed_text(p[0], 6) + " Y" + fixed_text(p[1], 6) + " Z" + fixed_text(p[2], 6);
  };
  const auto arc = [&](const char* g, double from_deg, double to_deg) {
    return std::string(g) + " " + point(to_deg) + centre_words(c, c.at(from_deg * M_PI / 180)) + "\n";
  };
  const double in = kFeedInRad * 180 / M_PI;
  std::ostringstream g;
  g << "(volcomp acceptance plan: ISO 230-4 circular test " << c.name << " of " << model.info.name << ")\n"
    << "(ballbar of " << number_text(c.radius_mm) << " mm in " << c.plane << " about X Y Z " << fixed_text(c.centre_mm[0], 3)
    << ", " << fixed_text(c.centre_mm[1], 3) << ", " << fixed_text(c.centre_mm[2], 3) << " mm [joints], the setup sheet "
    << c.name << ".md)\n"
    << "G21 G90 G94 G40 G80 " << plane_word(c) << "\n"
    << "G43.1 Z" << fixed_text(plan.tool_offset_mm, 6) << " (the tool ball's L " << number_text(plan.settings.tool_length_mm)
    << " mm minus tool_length_reference_mm)\n";
  std::string rotary;
  for (int k = 0; k < model.joint_count(); ++k) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(k)];
    if (a.type == machine::AxisType::Rotary) rotary += std::string(" ") + a.letter + number_text(plan.rest[k]);
  }
  if (!rotary.empty()) g << "G0" << rotary << " (rotary axes at rest for the whole test)\n";
  g << "G0 " << point(0) << " (the start, 0 deg: the tool ball here, fit the ballbar)\n"
    << "M1 (optional stop: fit the ballbar, start its capture)\n"
    << "F" << number_text(plan.settings.feed_mm_per_min) << "\n"
    << "(counterclockwise: feed-in " << number_text(in) << " deg, the full turn, feed-out " << number_text(in) << " deg)\n"
    << arc("G2", 0, -in) << arc("G3", -in, 180) << arc("G3", 180, in) << "G4 P1\n"
    << "(clockwise: feed-in, the full turn, feed-out)\n"
    << arc("G2", in, -180) << arc("G2", -180, -in) << arc("G3", -in, 0) << "G49\nM2\n";
  return g.str();
}

std::string circle_sheet(const Plan& plan, const Circle& c, const machine::Model& model) {
  std::ostringstream m;
  const std::string first(1, c.plane[0]), second(1, c.plane[1]);
  m << "# ISO 230-4 circular test " << c.name << ", " << model.info.name << "\n\n"
    << "Machine file `" << plan.machine << "`. Program `" << c.name << ".ngc` (in this folder), run in LinuxCNC "
    << "with the compensation as it will be used (ISO/TR 16907 11.3: all compensations active by default).\n\n"
    << "| | |\n|---|---|\n"
    << "| plane | " << c.plane << " (angles from +" << first << " towards +" << second << "; ccw the increasing angle) |\n"
    << "| centre | X Y Z = " << fixed_text(c.centre_mm[0], 3) << ", " << fixed_text(c.centre_mm[1], 3) << ", "
    << fixed_text(c.centre_mm[2], 3) << " mm (joints) |\n"
    << "| radius | " << number_text(c.radius_mm) << " mm: the ballbar's length |\n"
    << "| tool-side ball | on the spindle axis, L = " << number_text(plan.settings.tool_length_mm)
    << " mm below the spindle gauge point: the effective tool-side offset of ISO/TR 16907 11.3 a) |\n"
    << "| tool length to declare | the program declares it: G43.1 Z" << number_text(plan.tool_offset_mm)
    << " (L minus the machine file's tool_length_reference_mm), so volkins corrects for the ball |\n"
    << "| feed | " << number_text(plan.settings.feed_mm_per_min) << " mm/min (contouring, G2/G3) |\n"
    << "| runs | counterclockwise then clockwise, each a full turn with 10 deg feed-in and feed-out arcs |\n\n"
    << "## Setup\n\n"
    << "1. The centre pivot on the table (the part side): with the tool cup in the spindle at L, put the tool "
       "ball at the centre above and lock the pivot there (the setting arm).\n"
    << "2. Run the program: it goes to the start (0 deg) and stops at M1 (optional stop on): fit the ballbar "
       "and start its capture, then resume.\n"
    << "3. Export the run as `" << c.name << ".csv` in the measurements folder, the layout `volcomp identify "
       "circle` reads, with these lines first:\n\n"
    << "       # plane: " << c.plane << "\n       # radius_mm: " << number_text(c.radius_mm)
    << "\n       # tool_length_mm: " << number_text(plan.settings.tool_length_mm) << "\n"
    << "       angle[deg],direction,deviation[um]\n\n"
    << "   angle from +" << first << " towards +" << second << " over the full turn; direction ccw or cw; deviation "
       "= the ballbar's length minus its nominal length (+: longer).\n";
  return m.str();
}

}  // namespace vc::acceptance
