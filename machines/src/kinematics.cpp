#include "vc/machine/kinematics.hpp"

#include <cmath>

#include "vc/machine/held_rotary.hpp"
#include "vc/machine/ideal_jacobian_solver.hpp"

namespace vc::machine {

Status nominal_inverse(const Model& model, WorldConvention convention, const Joints& world, double tool_length_mm,
                       Joints& nominal) noexcept {
  nominal = world;
  if (!world.allFinite()) return Status::NonFinite;
  if (convention == WorldConvention::Axes) return Status::Ok;
  // Tcp: rotary joints are given; the ideal tip is affine in the linear joints, so Newton
  // lands in one step and the second confirms it.
  const int n = model.joint_count();
  IdealJacobianSolver solver(model, 0);  // the linear joints, by their 3 x 3 block
  if (!solver.applies()) return Status::Singular;
  PoseDerivatives d;
  for (int step = 0; step <= model.solver.max_iterations; ++step) {
    const ToolPose pose = tool_pose(model, Machine::Ideal, nominal, tool_length_mm, d);
    Eigen::Vector3d tip_target;
    int c = 0;
    for (int j = 0; j < n; ++j)
      if (model.axes[j].type == AxisType::Linear) tip_target[c++] = world[j];
    const Eigen::Vector3d residual = pose.tip_mm - tip_target;
    if (!residual.allFinite()) return Status::NonFinite;
    if (residual.norm() <= model.solver.position_tolerance_mm) return Status::Ok;
    if (!solver.factorize(position_target(pose), d)) return Status::Singular;
    const Joints dq = solver.solve(Joints(residual));
    if (!dq.allFinite()) return Status::Singular;
    nominal -= dq;
  }
  return Status::NotConverged;
}

Joints nominal_forward(const Model& model, WorldConvention convention, const Joints& nominal,
                       double tool_length_mm) noexcept {
  Joints world = nominal;
  if (convention == WorldConvention::Axes) return world;
  const ToolPose pose = tool_pose(model, Machine::Ideal, nominal, tool_length_mm);
  int c = 0;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[j].type == AxisType::Linear) world[j] = pose.tip_mm[c++];
  return world;
}

namespace {

double nominal_length(const Applied& applied, double tool_length_mm) {
  return std::isnan(applied.nominal_tool_length_mm) ? tool_length_mm : applied.nominal_tool_length_mm;
}

bool near(const Joints* seed, const Joints& point) {
  return seed && seed->size() == point.size() && seed->allFinite() &&
         (*seed - point).cwiseAbs().maxCoeff() <= Applied::kSeedRadius;
}

}  // namespace

Status joints_from_world(const Model& model, WorldConvention convention, const Joints& world, double tool_length_mm,
                         Joints& joints, Correction* report) noexcept {
  return joints_from_world(model, convention, world, tool_length_mm, Applied{}, joints, report);
}

Status world_from_joints(const Model& model, WorldConvention convention, const Joints& joints, double tool_length_mm,
                         Joints& world) noexcept {
  return world_from_joints(model, convention, joints, tool_length_mm, Applied{}, world);
}

Status joints_from_world(const Model& model, WorldConvention convention, const Joints& world, double tool_length_mm,
                         const Applied& applied, Joints& joints, Correction* report) noexcept {
  Joints nominal;
  const Status s = nominal_inverse(model, convention, world, nominal_length(applied, tool_length_mm), nominal);
  if (s != Status::Ok) return s;
  const Conditions& conditions = applied.conditions ? *applied.conditions : model.reference_conditions();
  if (applied.held && applied.held->any(model)) {  // a clamped rotary joint keeps its correction
    const Correction c = correct_held(model, conditions, nominal, tool_length_mm, applied.gain, *applied.held,
                                      near(applied.seed, nominal) ? *applied.seed : nominal);
    if (report) *report = c;
    if (c.status != Status::Ok) return c.status;
    joints = c.joints;
    return Status::Ok;
  }
  if (applied.gain == 0.0) {
    joints = nominal;
    if (report) {
      *report = Correction{};
      report->nominal = report->joints = nominal;
    }
    return Status::Ok;
  }
  const bool extrapolated = usable_correction(applied.correction, nominal);
  const Joints seed = extrapolated               ? Joints(nominal + *applied.correction)
                      : near(applied.seed, nominal) ? *applied.seed
                                                    : nominal;
  const bool full_seeded = usable_correction(applied.full_correction, nominal);
  const Joints full_seed = full_seeded ? Joints(nominal + *applied.full_correction) : Joints();
  // The contraction bound describes steps from next to the answer (the extrapolation of the
  // last corrections): from LinuxCNC's last joints, a servo period of motion away, the nominal
  // machine's own curvature is in no sampled kappa, and where kappa is ~0 (a machine with small
  // errors) one unevaluated step would stop micrometres short. Every step is evaluated then.
  const Correction c = correct(model, conditions, nominal, tool_length_mm, seed,
                               extrapolated ? applied.contraction : nullptr, full_seeded ? &full_seed : nullptr);
  if (report) *report = c;
  if (c.status != Status::Ok) return c.status;
  joints = nominal + applied.gain * (c.joints - nominal);
  return Status::Ok;
}

Status world_from_joints(const Model& model, WorldConvention convention, const Joints& joints, double tool_length_mm,
                         const Applied& applied, Joints& world, int* iterations) noexcept {
  Joints nominal_seed = joints;
  if (usable_correction(applied.correction, joints)) {
    nominal_seed = joints - applied.gain * *applied.correction;
  } else if (applied.seed) {
    Joints from_seed;
    if (nominal_inverse(model, convention, *applied.seed, nominal_length(applied, tool_length_mm), from_seed) ==
            Status::Ok &&
        near(&from_seed, joints))
      nominal_seed = from_seed;
  }
  const Conditions& conditions = applied.conditions ? *applied.conditions : model.reference_conditions();
  const Uncorrection u =
      applied.held && applied.held->any(model)
          ? uncorrect_held(model, conditions, joints, tool_length_mm, applied.gain, *applied.held, nominal_seed)
          : invert_correction(model, conditions, joints, tool_length_mm, applied.gain, nominal_seed,
                              applied.full_correction);
  if (iterations) *iterations = u.iterations;
  if (u.status != Status::Ok) return u.status;
  world = nominal_forward(model, convention, u.nominal, nominal_length(applied, tool_length_mm));
  return Status::Ok;
}

}  // namespace vc::machine
