#include "vc/acceptance/rtest_program.hpp"

#include <sstream>

#include "vc/tables/number_text.hpp"

namespace vc::acceptance {
namespace {

// Every joint of a pose as G-code words, Z less the program's G43.1 offset (axes world).
std::string words(const Plan& plan, const machine::Model& model, const machine::Joints& q) {
  std::string w;
  for (int j = 0; j < model.joint_count(); ++j) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    w += std::string(w.empty() ? "" : " ") + a.letter + fixed_text(q[j] - (a.letter == 'Z' ? plan.tool_offset_mm : 0.0), 6);
  }
  return w;
}

}  // namespace

std::string rtest_program(const Plan& plan, const machine::Model& model) {
  const RTestPlan& r = plan.rtest;
  std::ostringstream g;
  g << "(volcomp acceptance plan: ISO 10791-6 R-test of " << model.info.name << ", the setup sheet rtest.md)\n"
    << "(the sphere where the nest sits on it at X Y Z " << fixed_text(r.sphere_joints_mm[0], 3) << ", "
    << fixed_text(r.sphere_joints_mm[1], 3) << ", " << fixed_text(r.sphere_joints_mm[2], 3)
    << " mm, rotary axes at 0; each pose approached along the tool from " << number_text(kRTestRetractMm) << " mm back)\n"
    << "G21 G90 G94 G17 G40 G80\n"
    << "G43.1 Z" << fixed_text(plan.tool_offset_mm, 6) << " (the nest's L " << number_text(plan.settings.tool_length_mm)
    << " mm minus tool_length_reference_mm)\n"
    << "F" << number_text(plan.settings.feed_mm_per_min) << "\n";
  int pose = 0;
  for (const RTestSequence& s : r.sequences) {
    g << "(" << s.name << ": " << s.poses.size() << " poses)\n";
    for (std::size_t k = 0; k < s.poses.size(); ++k) {
      g << "G0 " << words(plan, model, s.retracts[k]) << " (pose " << ++pose << ": its retract)\n"
        << "G1 " << words(plan, model, s.poses[k]) << " (on the sphere)\n"
        << "G4 P" << number_text(plan.settings.dwell_s) << "\n"
        << "G1 " << words(plan, model, s.retracts[k]) << "\n";
    }
  }
  g << "G49\nM2\n";
  return g.str();
}

std::string rtest_sheet(const Plan& plan, const machine::Model& model) {
  const RTestPlan& r = plan.rtest;
  std::ostringstream m;
  m << "# ISO 10791-6 R-test, " << model.info.name << "\n\n"
    << "Machine file `" << plan.machine << "`. Program `rtest.ngc` (in this folder), run in LinuxCNC with the "
       "compensation as it will be used.\n\n"
    << "| | |\n|---|---|\n"
    << "| sphere | on the table; its centre where the nest's centre is at X Y Z = " << fixed_text(r.sphere_joints_mm[0], 3)
    << ", " << fixed_text(r.sphere_joints_mm[1], 3) << ", " << fixed_text(r.sphere_joints_mm[2], 3)
    << " mm (joints), rotary axes at 0: " << fixed_text(r.sphere_mm[0], 3) << ", " << fixed_text(r.sphere_mm[1], 3)
    << ", " << fixed_text(r.sphere_mm[2], 3) << " mm in the part frame (the ideal machine) |\n"
    << "| sensor nest | in the spindle, its centre L = " << number_text(plan.settings.tool_length_mm)
    << " mm below the gauge point; the program declares it: G43.1 Z" << number_text(plan.tool_offset_mm) << " |\n"
    << "| moves | each pose approached and left along the tool from " << number_text(kRTestRetractMm)
    << " mm back (G1 F" << number_text(plan.settings.feed_mm_per_min) << "); between poses the nest moves at the "
       "retract in joint space: check that it clears the set-up |\n"
    << "| dwell | " << number_text(plan.settings.dwell_s) << " s on the sphere: take the reading in it |\n\n"
    << "## Setup\n\n"
    << "1. Fix the sphere on the table; with the rotary axes at 0 bring the nest onto it at the joints above "
       "(adjust the sphere, not the joints) and zero the three sensors there.\n"
    << "2. Run the program; at each dwell record the three readings.\n"
    << "3. Export them as `" << kRTestMeasurements << "` in the measurements folder, one pose per row in the "
       "program's order, the layout `volcomp identify rtest` reads:\n\n"
    << "       " << [&] {
         std::string h;
         for (char c : plan.coordinates) h += std::string(1, c) + ",";
         return h + "dx[um],dy[um],dz[um]";
       }()
    << "\n\n   the commanded joints (the pose's, below) and the sphere's centre against the nest's along the spindle "
       "frame's x, y, z (error = actual - nominal).\n\n## Poses\n\n";
  for (const RTestSequence& s : r.sequences) {
    m << "### " << s.name << " (" << s.poses.size() << " poses"
      << (s.left_out ? ", " + std::to_string(s.left_out) + " left out: their joints leave the travel" : "") << ")\n\n| ";
    for (char c : plan.coordinates) m << c << " | ";
    m << "\n|";
    for (std::size_t j = 0; j < plan.coordinates.size(); ++j) m << "---:|";
    m << "\n";
    for (const machine::Joints& q : s.poses) {
      m << "| ";
      for (int j = 0; j < q.size(); ++j) m << fixed_text(q[j], 3) << " | ";
      m << "\n";
    }
    m << "\n";
  }
  return m.str();
}

}  // namespace vc::acceptance
