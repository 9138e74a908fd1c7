#include "vc/identify/probe_plan.hpp"

#include <cmath>
#include <stdexcept>

#include "vc/machine/forward.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::identify {
namespace {

// G-code words to 0.1 um, never "-0.0000".
std::string number(double v) { return without_negative_zero(fixed_text(v, 4)); }

}  // namespace

std::string probe_plan(const machine::Model& model, const ProbePlanOptions& o) {
  const int x = model.joint_of('X'), y = model.joint_of('Y'), z = model.joint_of('Z');
  if (x < 0 || y < 0 || z < 0) throw std::runtime_error("probing a sphere needs X, Y and Z axes");
  std::vector<int> rotary;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary) rotary.push_back(j);
  if (rotary.empty()) throw std::runtime_error(model.info.name + " has no rotary axis to locate");
  const double length = o.probe_length_mm > 0 ? o.probe_length_mm : model.tool_length_mm;
  const double reach = (o.sphere_diameter_mm + o.ball_diameter_mm) / 2;  // ball centre from the sphere's on contact
  const double safe = o.safe_z_mm != 0.0 ? o.safe_z_mm : model.axes[static_cast<std::size_t>(z)].travel_max;

  // The sphere's centre: a point of the part frame, where the ideal tip is at rotary 0.
  machine::Joints q0 = machine::Joints::Zero(model.joint_count());
  q0[x] = o.centre_mm.x(), q0[y] = o.centre_mm.y(), q0[z] = o.centre_mm.z();
  const Eigen::Vector3d p0 = machine::tool_pose(model, machine::Machine::Ideal, q0, length).tip_mm;

  const auto within = [&](int j, double v, int pose) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    if (v < a.travel_min - 1e-9 || v > a.travel_max + 1e-9)
      throw std::runtime_error("pose " + std::to_string(pose) + ": " + std::string(1, a.letter) + " " + number(v) +
                               " is outside the travel " + number(a.travel_min) + " .. " + number(a.travel_max));
    return number(v);
  };
  if (!(o.back_off_mm > 0) || !(o.back_off_mm < o.clearance_mm) || !(o.probe_feed_mm_min > 0) ||
      !(o.touch_feed_mm_min > 0))
    throw std::runtime_error("the feeds must be positive and the back-off between 0 and the clearance");
  // One probed point: a search at the probe feed from `clearance` off the surface, a back-off,
  // and the measuring touch at the touch feed (its trip is the one logged). LinuxCNC latches
  // the position of the servo cycle in which the probe input is seen: the trip lies up to
  // touch feed x servo period past the contact (10 mm/min, 1 ms: 0.17 um), where a single
  // touch at the search feed would be 1.7 um off.
  const auto touch = [&](int dx, int dy, int dz) {  // the approach direction
    const auto move = [&](double distance) {
      return dz != 0 ? " Z" + number(dz * distance) : " X" + number(dx * distance) + " Y" + number(dy * distance);
    };
    return "G91 G38.2" + move(2 * o.clearance_mm) + " F" + number(o.probe_feed_mm_min) + "\n" + "G0" +
           move(-o.back_off_mm) + "\n" + "G38.2" + move(2 * o.back_off_mm) + " F" + number(o.touch_feed_mm_min) +
           "\nG90\n";
  };
  std::string out;
  out += "(volcomp probe-plan: " + model.info.name + ", a sphere of " + number(o.sphere_diameter_mm) +
         " mm probed with a " + number(o.ball_diameter_mm) + " mm ball at " +
         std::to_string(o.rotary_positions.size()) + " rotary positions)\n";
  out += "(run with the compensation OFF, G54 active, no G92, the probe in the spindle; the log goes to " + o.log_file +
         ")\n";
  out += "(then: volcomp identify sphere MACHINE " + o.log_file + ")\n";
  out += "G21 G90 G94 G17 G40 G49 G80 G92.1 G54\n";
  out += "(LOGOPEN," + o.log_file + ")\n";
  std::string axes;
  for (int j = 0; j < model.joint_count(); ++j)
    axes += static_cast<char>(std::tolower(model.axes[static_cast<std::size_t>(j)].letter));
  out += "(LOG,# volcomp probe log: sphere_diameter_mm " + number(o.sphere_diameter_mm) + " ball_diameter_mm " +
         number(o.ball_diameter_mm) + " probe_length_mm " + number(length) + " axes " + axes + ")\n";
  out += "G53 G0 Z" + number(safe) + "\n";
  int pose = 0;
  for (const std::vector<double>& position : o.rotary_positions) {
    ++pose;
    if (position.size() != rotary.size())
      throw std::runtime_error("pose " + std::to_string(pose) + ": " + std::to_string(rotary.size()) +
                               " rotary positions expected");
    machine::Joints q = q0;
    std::string rotary_words, rotary_log;
    for (std::size_t r = 0; r < rotary.size(); ++r) {
      q[rotary[r]] = position[r];
      rotary_words += " " + std::string(1, model.axes[static_cast<std::size_t>(rotary[r])].letter) +
                      within(rotary[r], position[r], pose);
      rotary_log += " " + number(position[r]);
    }
    // X Y Z that put the ideal tip on the centre with the table turned (Newton, the linear axes).
    for (int step = 0; step < 20; ++step) {
      const Eigen::Vector3d rr = machine::tool_pose(model, machine::Machine::Ideal, q, length).tip_mm - p0;
      if (rr.norm() < 1e-9) break;
      Eigen::Matrix3d j;
      const int lin[3] = {x, y, z};
      for (int i = 0; i < 3; ++i) {
        machine::Joints h = q;
        h[lin[i]] += 1.0;
        j.col(i) = machine::tool_pose(model, machine::Machine::Ideal, h, length).tip_mm - p0 - rr;
      }
      const Eigen::Vector3d dq = j.lu().solve(-rr);
      for (int i = 0; i < 3; ++i) q[lin[i]] += dq[i];
    }
    const double cx = q[x], cy = q[y], cz = q[z], above = cz + reach + o.clearance_mm;
    const std::string log =
        "(LOG,POINT " + std::to_string(pose) + rotary_log + " #5061 #5062 #5063 #5221 #5222 #5223)\n";
    out += "(pose " + std::to_string(pose) + ":" + rotary_words + ")\n";
    out += "G53 G0 Z" + within(z, safe, pose) + "\n";
    out += "G53 G0" + rotary_words + "\n";
    out += "G53 G0 X" + within(x, cx, pose) + " Y" + within(y, cy, pose) + "\n";
    out += "G53 G0 Z" + within(z, above, pose) + "\n";
    out += touch(0, 0, -1) + log;
    out += "G91 G0 Z" + number(o.clearance_mm) + "\nG90\n";
    for (const auto& [sx, sy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
      const double px = cx + sx * (reach + o.clearance_mm), py = cy + sy * (reach + o.clearance_mm);
      out += "G53 G0 Z" + within(z, above, pose) + "\n";
      out += "G53 G0 X" + within(x, px, pose) + " Y" + within(y, py, pose) + "\n";
      out += "G53 G1 Z" + within(z, cz, pose) + " F" + number(o.rapid_feed_mm_min) + "\n";
      out += touch(-sx, -sy, 0) + log;
      out += "G91 G0 X" + number(sx * o.clearance_mm) + " Y" + number(sy * o.clearance_mm) + "\nG90\n";
    }
    out += "G53 G0 Z" + number(above) + "\n";
  }
  out += "G53 G0 Z" + number(safe) + "\n(LOGCLOSE)\nM2\n";
  return out;
}

}  // namespace vc::identify
