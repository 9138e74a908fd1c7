// volcomp trace: the tool-tip error of a recorded LinuxCNC session, and whether volkins did
// exactly what the core computes (see vc/trace/session_trace.hpp for the comparison).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "commands.hpp"
#include "format.hpp"
#include "program_files.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/atomic_file.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc::cli {

int run_trace(const TraceArgs& args, std::ostream& out) {
  const machine::Model model = machine::load_machine(args.machine);
  const machine::WorldConvention convention = world_convention(args.world);
  const trace::SessionTrace session = trace::read_session_trace(args.trace, model);
  const trace::TraceSummary summary = trace::check_trace(model, convention, session);
  if (summary.samples.empty()) throw std::runtime_error(args.trace + ": fewer than 4 usable samples");

  double max_tip = 0, sum_sq = 0, max_dir = 0, max_mismatch = 0, max_pose_mm = 0, max_pose_rad = 0;
  for (const trace::SampleCheck& s : summary.samples) {
    const double e = s.tip_error_mm.norm();
    max_tip = std::max(max_tip, e);
    sum_sq += e * e;
    max_dir = std::max(max_dir, s.direction_error_rad);
    max_mismatch = std::max(max_mismatch, s.module_mismatch);
    if (s.full_correction) {
      max_pose_mm = std::max(max_pose_mm, s.command_pose_mm);
      max_pose_rad = std::max(max_pose_rad, s.command_pose_rad);
    }
  }
  const double rms = std::sqrt(sum_sq / static_cast<double>(summary.samples.size()));

  if (!args.output.empty()) tables::write_atomically(args.output, [&](std::ostream& csv) {
    csv << "t_s,ex_um,ey_um,ez_um,e_um,ek_urad,gain\n";
    for (const trace::SampleCheck& s : summary.samples) {
      csv << format_fixed(static_cast<double>(s.sample) * args.servo_period_s, 3);
      // Full precision: with compensation on, the errors are nanometres.
      for (int k = 0; k < 3; ++k) csv << ',' << format_number(s.tip_error_mm[k] * 1e3);
      csv << ',' << format_number(s.tip_error_mm.norm() * 1e3) << ',' << format_number(s.direction_error_rad * 1e6)
          << ',' << format_number(session.gain[s.sample]) << '\n';
    }
  });
  out << "trace: " << args.trace << " (" << summary.samples.size() << " samples checked, " << summary.skipped
      << " skipped at tool changes)\n"
      << "tool tip error: max " << format_fixed(max_tip * 1e3, 3) << " um, RMS " << format_fixed(rms * 1e3, 3)
      << " um; tool direction error: max " << format_fixed(max_dir * 1e6, 2) << " urad\n";
  if (!session.with_volkins) {
    // LinuxCNC's own kinematics: what moves the joints off them is the joints' COMP_FILEs.
    out << "joints beyond the nominal kinematics' (COMP_FILE corrections; mm or deg): max "
        << format_number(max_mismatch) << '\n';
    return 0;
  }
  out << "module against the core (joints, mm or deg): max " << format_number(max_mismatch) << '\n'
      << "commanded pose residual where fully corrected: max " << format_number(max_pose_mm) << " mm, "
      << format_number(max_pose_rad) << " rad\n";
  return 0;
}

}  // namespace vc::cli
