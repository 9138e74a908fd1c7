#include "vc/fit_tables/comp_file.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "vc/tables/number_text.hpp"

namespace vc::fit_tables {
namespace {

constexpr int kCompSize = 256;  // EMCMOT_COMP_SIZE

}  // namespace

double reversal_at(const JointReversal& r, double position) {
  if (r.target.empty()) return 0.0;
  if (position <= r.target.front()) return r.reversal.front();
  if (position >= r.target.back()) return r.reversal.back();
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(r.target.begin(), r.target.end(), position) -
                                                 r.target.begin());  // 1 .. size - 1
  const double f = (position - r.target[k - 1]) / (r.target[k] - r.target[k - 1]);
  return r.reversal[k - 1] + f * (r.reversal[k] - r.reversal[k - 1]);
}

std::vector<LinuxcncCompFile> linuxcnc_comp_files(const machine::Model& model, const TableSet& set,
                                                  const Eigen::VectorXd& x,
                                                  const std::vector<JointReversal>& reversals) {
  std::vector<LinuxcncCompFile> files;
  for (const Table& t : set.tables) {
    if (t.kind != TableKind::Positioning)
      throw std::invalid_argument("a LinuxCNC COMP_FILE holds a joint's own positioning only, not the " +
                                  std::string(kind_name(t.kind)) + " table " + set.name(model, t));
    if (static_cast<int>(t.nodes.size()) > kCompSize)
      throw std::invalid_argument("LinuxCNC takes at most 256 points per COMP_FILE (EMCMOT_COMP_SIZE); table " +
                                  set.name(model, t) + " has " + std::to_string(t.nodes.size()));
    LinuxcncCompFile f;
    f.joint = t.input;
    f.axis = model.axes[static_cast<std::size_t>(t.input)].letter;
    f.file_name = linuxcnc_comp_file_name(model, f.joint);
    const auto r =
        std::find_if(reversals.begin(), reversals.end(), [&](const JointReversal& j) { return j.joint == f.joint; });
    // No comment or header line: LinuxCNC stops reading at the first line that is not three numbers.
    for (std::size_t k = 0; k < t.nodes.size(); ++k) {
      const double value = x[t.unknown_of_node(static_cast<int>(k))];
      const double half_b = r == reversals.end() ? 0.0 : 0.5 * reversal_at(*r, t.nodes[k]);
      f.text += number_text(t.nodes[k]) + " " + number_text(value - half_b) + " " + number_text(value + half_b) + "\n";
    }
    files.push_back(std::move(f));
  }
  for (const JointReversal& r : reversals)
    if (std::none_of(files.begin(), files.end(), [&](const LinuxcncCompFile& f) { return f.joint == r.joint; }))
      throw std::invalid_argument("a reversal for joint " + std::to_string(r.joint) + " (" +
                                  model.axes[static_cast<std::size_t>(r.joint)].letter +
                                  "), which has no positioning table to put it in");
  return files;
}

std::string linuxcnc_ini_lines(const std::vector<LinuxcncCompFile>& files) {
  std::string s =
      "# volcomp fit-tables: the joints' compensation tables (COMP_FILE_TYPE 1: nominal position, forward and\n"
      "# reverse correction added to the joint's command, machine units). Paths are relative to the INI's\n"
      "# folder (linuxcnc runs there). A joint with a COMP_FILE ignores its BACKLASH: a reversal measured by\n"
      "# laser goes into the forward and reverse columns (volcomp fit-tables --reversal AXIS=runs.csv).\n";
  for (const LinuxcncCompFile& f : files)
    s += "[JOINT_" + std::to_string(f.joint) + "]\nCOMP_FILE = " + f.file_name + "\nCOMP_FILE_TYPE = 1\n";
  return s;
}

std::string linuxcnc_comp_file_name(const machine::Model& model, int joint) {
  return "joint_" + std::to_string(joint) + "_" +
         static_cast<char>(
             std::tolower(static_cast<unsigned char>(model.axes[static_cast<std::size_t>(joint)].letter))) +
         ".comp";
}

LinuxcncComp read_linuxcnc_comp(const std::string& text, int type) {
  LinuxcncComp c;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    double nom, fwd, rev;
    if (std::sscanf(line.c_str(), "%lf %lf %lf", &nom, &fwd, &rev) != 3) break;  // as usrmotLoadComp
    const double forward_trim = type == 0 ? nom - fwd : fwd, reverse_trim = type == 0 ? nom - rev : rev;
    if (static_cast<int>(c.nominal.size()) >= kCompSize)
      throw std::invalid_argument("more than 256 compensation entries (LinuxCNC: too many compensation entries)");
    if (!c.nominal.empty() && nom <= c.nominal.back())
      throw std::invalid_argument("compensation nominal " + number_text(nom) +
                                  " does not increase (LinuxCNC: compensation "
                                  "values must increase)");
    if (!c.nominal.empty()) {  // the slope from the previous entry, stored as float
      const double width = nom - c.nominal.back();
      c.forward_slope.back() = static_cast<float>((static_cast<float>(forward_trim) - c.forward_trim.back()) / width);
      c.reverse_slope.back() = static_cast<float>((static_cast<float>(reverse_trim) - c.reverse_trim.back()) / width);
    }
    c.nominal.push_back(nom);
    c.forward_trim.push_back(static_cast<float>(forward_trim));
    c.reverse_trim.push_back(static_cast<float>(reverse_trim));
    c.forward_slope.push_back(0.0f);
    c.reverse_slope.push_back(0.0f);
  }
  return c;
}

double linuxcnc_comp_value(const LinuxcncComp& c, double position, bool forward) {
  if (c.nominal.empty()) return 0.0;
  const std::vector<float>& trim = forward ? c.forward_trim : c.reverse_trim;
  const std::vector<float>& slope = forward ? c.forward_slope : c.reverse_slope;
  if (position < c.nominal.front()) return trim.front();  // the -DBL_MAX entry: the first trim, slope 0
  std::size_t k = 0;
  while (k + 1 < c.nominal.size() && position >= c.nominal[k + 1]) ++k;
  return trim[k] + slope[k] * (position - c.nominal[k]);
}

double LinuxcncCompJoint::next(double position, double velocity) {
  if (velocity != 0.0) {
    target_ = linuxcnc_comp_value(*comp_, position, velocity > 0.0);
    moved_ = true;
  }
  ramp();
  return output_;
}

void LinuxcncCompJoint::moved_before(double position, int direction) {
  if (direction == 0) return;
  target_ = output_ = linuxcnc_comp_value(*comp_, position, direction > 0);
  rate_ = 0.0;
  moved_ = true;
}

// The ramp, written for a target above the output; a target below is the mirror image (output,
// target and rate negated), which is how LinuxCNC's two branches relate.
void LinuxcncCompJoint::ramp() {
  const double sign = target_ >= output_ ? 1.0 : -1.0;
  const double to_go = sign * (target_ - output_);
  if (to_go <= 0.0) return;
  double v = sign * rate_;  // towards the target
  const double cruise = v * dt_;
  double dv = a_max_ * dt_;
  double stop = 0.5 * (v + dv) * (v + dv) / a_max_;
  double step = 0.0;
  if (to_go <= stop + cruise) {  // time to decelerate
    if (v > dv) {
      step = cruise - 0.5 * dv * dt_;
      v -= dv;
    } else {  // one period's deceleration covers the rest: land on the target
      output_ = target_;
      rate_ = 0.0;
      return;
    }
  } else {
    if (v + dv > v_max_) dv = v_max_ - v;
    const double accelerate = 0.5 * dv * dt_;
    stop = 0.5 * (v + dv) * (v + dv) / a_max_;
    if (to_go > stop + cruise + accelerate) {
      step = cruise + accelerate;
      v += dv;
    } else {
      step = cruise;
    }
  }
  output_ += sign * step;
  rate_ = sign * v;
}

}  // namespace vc::fit_tables
