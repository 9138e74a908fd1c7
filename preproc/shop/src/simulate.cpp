#include <algorithm>
#include <cmath>
#include <string>

#include "move_sampling.hpp"
#include "program_blocks.hpp"
#include "program_points.hpp"
#include "vc/machine/forward.hpp"
#include "vc/shop/tool_path.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::shop {
namespace {

using interpreter::Move;
using interpreter::MoveKind;
using interpreter::Position;

class Simulator {
 public:
  Simulator(const machine::Model& machine, const interpreter::Setup& setup, const SimulationOptions& options)
      : machine_(machine), setup_(setup), options_(options), points_(machine, options.world, setup.file) {}

  void run(const Move& m, int number, const std::function<void(const PathSample&)>& sink) {
    const int n = piece_count(m, options_.step_mm, options_.chord_tolerance_mm, options_.step_deg);
    const bool cutting = m.kind != MoveKind::Rapid && m.spindle_on;
    PathSample sample;
    sample.move = number;
    sample.line = m.line;
    sample.tool = m.tool;
    sample.radius_mm = radius_of(m.tool);
    sample.end = options_.ball_end_tools.count(m.tool) ? ToolEnd::Ball : ToolEnd::Flat;
    sample.cutting = cutting;
    const double L = machine_.correction_length(m.tool_offset_mm);  // the tool-length rule
    sample.tool_length_mm = L;
    for (int k = 0; k <= n; ++k) {
      sample.s = static_cast<double>(k) / n;
      sample.program = interpreter::point_at(m, sample.s);
      const machine::Joints world = points_.world(m, sample.program);
      const machine::Joints nominal = points_.nominal(m, world);
      sample.joints = nominal;
      if (options_.compensation) {
        machine::Applied applied;
        applied.conditions = options_.compensation_conditions;
        const machine::Status status = machine::joints_from_world(
            *options_.compensation, options_.world, world, options_.compensation->correction_length(m.tool_offset_mm),
            applied, sample.joints);
        if (status != machine::Status::Ok)
          throw LoadError({setup_.file, m.line}, "the compensation does not converge at this move");
      }
      const machine::ToolPose real = machine::tool_pose(machine_, machine::Machine::Real, sample.joints, L);
      const machine::ToolPose ideal = machine::tool_pose(machine_, machine::Machine::Ideal, nominal, L);
      sample.tip = real.tip_mm;
      sample.axis = real.direction;
      if (cutting && options_.deflection) sample.tip += deflection(m, sample.s, nominal, ideal);
      sample.error_mm = sample.tip - ideal.tip_mm;
      sink(sample);
    }
  }

 private:
  double radius_of(int tool) const {
    if (!setup_.tools) return 0.0;
    const auto it = setup_.tools->find(tool);
    return it == setup_.tools->end() ? 0.0 : it->second.diameter / 2;
  }

  // Deflection under the move's mean cutting force at fraction s (part frame, mm). The force
  // follows the ideal tip's direction of travel there.
  Eigen::Vector3d deflection(const Move& m, double s, const machine::Joints& nominal,
                             const machine::ToolPose& ideal) const {
    constexpr double ds = 1e-4;
    auto ideal_tip = [&](double at) {
      return points_.ideal_tip(m, interpreter::point_at(m, std::clamp(at, 0.0, 1.0)));
    };
    const Eigen::Vector3d feed = ideal_tip(s + ds) - ideal_tip(s - ds);
    if (feed.norm() < 1e-12) return Eigen::Vector3d::Zero();
    double length = 0;
    for (int i = 0; i < 3; ++i) length += (m.end[i] - m.start[i]) * (m.end[i] - m.start[i]);
    const Eigen::Vector3d force = options_.deflection->force(m, feed.normalized(), ideal.direction, std::sqrt(length));
    machine::Joints shift;
    Eigen::Vector3d delta;
    options_.deflection->at(nominal, machine_.correction_length(m.tool_offset_mm), force, shift, delta);
    return delta;
  }

  const machine::Model& machine_;
  const interpreter::Setup& setup_;
  const SimulationOptions& options_;
  ProgramPoints points_;
};

}  // namespace

void simulate(const machine::Model& machine, std::istream& program, const interpreter::Setup& setup,
              const SimulationOptions& options, const std::function<void(const PathSample&)>& sink) {
  if (options.compensation && options.compensation->coordinates() != machine.coordinates())
    throw LoadError({options.compensation->path}, "the compensation model's axes (" +
                                                      options.compensation->coordinates() +
                                                      ") are not the machine's (" + machine.coordinates() + ")");
  interpreter::Interpreter interpreter(setup);
  Simulator simulator(machine, setup, options);
  int moves = 0;
  for_each_block(program, interpreter, setup,
                 [&](const std::string&, const gcode::Block&, const interpreter::Effect& effect, int) {
                   for (const Move& m : effect.moves) simulator.run(m, ++moves, sink);
                 });
}

}  // namespace vc::shop
