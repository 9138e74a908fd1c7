#include "vc/fit_tables/comp_file_replay.hpp"

#include <algorithm>
#include <stdexcept>

#include "vc/fit_tables/evaluate.hpp"

namespace vc::fit_tables {

CompReplay replay_comp_files(const machine::Model& model, const trace::SessionTrace& session,
                             const trace::TraceSummary& summary, const std::vector<LinuxcncComp>& comps,
                             const std::vector<JointLimits>& limits, double servo_period_s) {
  const auto n_joints = static_cast<std::size_t>(model.joint_count());
  if (comps.size() != n_joints || limits.size() != n_joints)
    throw std::invalid_argument("a COMP_FILE replay needs a table (or none) and the limits of every joint");
  if (std::any_of(session.gain.begin(), session.gain.end(), [](double g) { return g != 0.0; }))
    throw std::invalid_argument(session.path +
                                ": volkins corrects in this session (its gain is not 0 throughout); "
                                "replay COMP_FILEs on a session without correction");
  std::vector<LinuxcncCompJoint> joints;
  for (std::size_t j = 0; j < n_joints; ++j) {
    joints.emplace_back(comps[j], limits[j].max_velocity, limits[j].max_acceleration, servo_period_s);
    if (session.size() > 0)
      joints[j].moved_before(session.world[0][static_cast<Eigen::Index>(j)], limits[j].homing_move);
  }
  CompReplay out;
  std::size_t next_check = 0;
  for (std::size_t n = 3; n < session.size() && next_check < summary.samples.size(); ++n) {
    // The nominal joints as LinuxCNC interpolates them, and joint.N.vel-cmd: the cubic
    // interpolator's slope, (p[n-1] - p[n-3]) / 2T.
    const machine::Joints q = trace::interpolated(session.world, n);
    const machine::Joints velocity = (session.world[n - 1] - session.world[n - 3]) / (2 * servo_period_s);
    machine::Joints commanded = q;
    for (std::size_t j = 0; j < n_joints; ++j)
      commanded[static_cast<Eigen::Index>(j)] +=
          joints[j].next(q[static_cast<Eigen::Index>(j)], velocity[static_cast<Eigen::Index>(j)]);
    if (summary.samples[next_check].sample != n) continue;
    out.tip_error_um.push_back(
        tip_error_um(model, commanded, {q, model.correction_length(session.tool_offset_mm[n - 1])}));
    out.settled.push_back(
        std::all_of(joints.begin(), joints.end(), [](const LinuxcncCompJoint& j) { return j.settled(); }));
    ++next_check;
  }
  return out;
}

}  // namespace vc::fit_tables
