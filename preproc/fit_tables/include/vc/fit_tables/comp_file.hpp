// LinuxCNC's [JOINT_n]COMP_FILE: the writer, and a reader and evaluator that do what LinuxCNC
// 2.9 does with the file (checked in its source, f1270d6ed7):
//   - usrmotLoadComp (src/emc/motion/usrmotintf.cc) reads "%lf %lf %lf" triplets line by line
//     and STOPS at the first line that is not three numbers (a comment line ends the table: the
//     written files have none); COMP_FILE_TYPE 0: nominal, actual position moving up, actual
//     moving down, turned into trims nominal - actual; type 1: nominal, forward trim, reverse
//     trim, taken as they are;
//   - EMCMOT_SET_JOINT_COMP (src/emc/motion/command.c) refuses a nominal that does not increase
//     and more than EMCMOT_COMP_SIZE (256) entries, and stores trims and the slopes to the next
//     entry as float (the value below the first entry is the first trim);
//   - compute_screw_comp (src/emc/motion/control.c): at the joint's commanded position pos_cmd,
//     trim + slope x (pos_cmd - nominal) of the entry at or below it, the forward values while the
//     joint moves up, the reverse ones while it moves down, held while it stands; the last
//     entry's slope stays 0 (held above it); the result is added to the motor command.
// The docs (docs/src/config/ini-config.adoc) call type 1's values "offset from nominal": the
// source adds them to the command, so they are corrections, as the fit's values are.
// Joint n is the machine's n-th axis in XYZABC order (trivkins and xyzbc-trt-kins
// configurations number them so, as kins/configs/mc300/mc300.ini does); values in machine units
// (mm and deg).
#pragma once

#include <string>
#include <vector>

#include "vc/fit_tables/table_set.hpp"

namespace vc::fit_tables {

struct LinuxcncCompFile {
  int joint = 0;
  char axis = 0;
  std::string file_name;  // "joint_0_x.comp"
  std::string text;       // COMP_FILE_TYPE 1 triplets: nominal, forward, reverse
};

// A joint's reversal error, measured by laser runs in both directions (ISO 230-2):
// B_i = x_i_up - x_i_down at each target (machine units, mm or deg). The model holds the mean
// bidirectional deviation, and the fitted values correct it; a COMP_FILE can also take the
// reversal, as LinuxCNC applies its forward column while the joint moves up and its reverse
// column while it moves down: forward = value - B/2, reverse = value + B/2 (each corrects its
// own direction's deviation), B interpolated linearly between the targets and held beyond them.
// Without it both columns are the same, and the reversal stays (a joint with a COMP_FILE
// ignores its BACKLASH).
struct JointReversal {
  int joint = 0;
  std::vector<double> target, reversal;  // ascending targets, B_i (mm or deg)
};

// B at `position`: linear between the targets, the end values held beyond them.
double reversal_at(const JointReversal& r, double position);

// One file per joint with a positioning table in `set` (values x), a joint in `reversals` with
// its forward and reverse columns apart. Throws std::invalid_argument for a table LinuxCNC has
// no place for (cross, squareness) or more than 256 nodes, and for a reversal of a joint
// without a file.
std::vector<LinuxcncCompFile> linuxcnc_comp_files(const machine::Model& model, const TableSet& set,
                                                  const Eigen::VectorXd& x,
                                                  const std::vector<JointReversal>& reversals = {});

// The lines to put in the configuration's INI file, per joint:
//   [JOINT_n]
//   COMP_FILE = joint_n_x.comp
//   COMP_FILE_TYPE = 1
std::string linuxcnc_ini_lines(const std::vector<LinuxcncCompFile>& files);

// The name fit-tables gives joint `joint`'s COMP_FILE: joint_<n>_<axis letter>.comp.
std::string linuxcnc_comp_file_name(const machine::Model& model, int joint);

// A COMP_FILE as LinuxCNC holds it after loading.
struct LinuxcncComp {
  std::vector<double> nominal;
  std::vector<float> forward_trim, reverse_trim, forward_slope, reverse_slope;
};

// Reads `text` as usrmotLoadComp + EMCMOT_SET_JOINT_COMP do. Throws std::invalid_argument
// where LinuxCNC would report an error (a nominal that does not increase, > 256 entries).
LinuxcncComp read_linuxcnc_comp(const std::string& text, int comp_file_type);

// compute_screw_comp's correction at `position` while the joint moves up (forward) or down.
double linuxcnc_comp_value(const LinuxcncComp& comp, double position, bool forward);

// One joint's correction servo period by servo period, as compute_screw_comp keeps it (the
// controller simulator of a LinuxCNC joint with a COMP_FILE):
//   - the target: the forward value while the commanded velocity is > 0, the reverse value while
//     it is < 0, the last target while it is 0; 0 until the joint first moves after LinuxCNC
//     starts (a joint the program never moves, or one homed without motion, is not corrected;
//     a homing's move to HOME counts: moved_before);
//   - what reaches the motor: the target through LinuxCNC's ramp, which moves towards it at
//     most at half the joint's MAX_VELOCITY and MAX_ACCELERATION (accelerating, cruising,
//     decelerating to stop on it, and landing on it at once when one period's deceleration
//     covers what is left). A table's values change by far less per period than that; only the
//     jump from 0 when a joint first moves (tens of um) takes a few periods.
class LinuxcncCompJoint {
 public:
  // max_velocity / max_acceleration: the joint's INI values (units/s, units/s^2).
  LinuxcncCompJoint(const LinuxcncComp& comp, double max_velocity, double max_acceleration, double servo_period_s)
      : comp_(&comp), v_max_(0.5 * max_velocity), a_max_(0.5 * max_acceleration), dt_(servo_period_s) {}
  // The correction added to the motor command in the period whose commanded position and
  // velocity (joint.N.pos-cmd, joint.N.vel-cmd) are given.
  double next(double position, double velocity);
  // The joint came to rest at `position` after a move up (direction +1) or down (-1) before the
  // first period given to next() (a homing's move to HOME): the correction is that direction's
  // value there.
  void moved_before(double position, int direction);
  // The joint has moved and the ramp has reached the table's value: the correction is the
  // table's (what the fit assumes everywhere).
  bool settled() const { return moved_ && output_ == target_; }

 private:
  void ramp();
  const LinuxcncComp* comp_;
  double v_max_, a_max_, dt_;
  double target_ = 0.0, output_ = 0.0, rate_ = 0.0;  // rate_: the ramp's signed velocity
  bool moved_ = false;
};

}  // namespace vc::fit_tables
