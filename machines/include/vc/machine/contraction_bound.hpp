// How much one Newton step of the correction gains, bounded over a machine's travel, so that a
// step can be taken without evaluating the real machine after it: the pre-distorter's
// one-step correction (preproc/predistort) and volkins' inverse in the servo thread
// (correct() with a bound, kinematics.hpp's Applied).
//
// The equations F(q) = 0 (correction_equations.hpp, the full correction: every joint free,
// 3 + rotary joints = joints) are solved by Newton with the ideal machine's Jacobian B at
// the target q_n, the core's first matrix. One step q+ = q - B^-1 F(q) leaves
// F(q+) = (B - Jbar) B^-1 F(q) exactly, Jbar the mean real Jacobian between q and q+ (mean
// value theorem), so |W F(q+)| <= kappa |W F(q)| with kappa = sup |W (B - J_real) B^-1 W^-1|
// (Frobenius; W weighs direction rows by kDirectionLeverMm), sampled over the travel (J_real
// at the core's corrected joints there) and doubled for what the sampling may miss. B^-1
// grows towards a kinematic pole, so kappa is kept per band of the pole angle (full
// correction angle x [1, 1.5), [1.5, 2), [2, 3), [3, ...), 100 samples each; one band on
// three linear axes). In the fade band (fade start <= phi < full) kappa sin(phi) is sampled
// instead, 100 samples and doubled, and kappa taken as that over sin(phi) (B^-1 grows as
// 1 / sin(phi) there): the inverse's full correction in the band, solved from the servo
// thread's extrapolation (~1e-10 off), is proved in one step as it is at full correction.
// The position's equations alone (the linear joints, the rotary ones held: correct()'s last
// solve where the fade is below 1) have their own kappa, (B - J) B^-1 of the position rows and
// the linear joints, sampled over the travel with J at the core's corrected joints: it does not
// grow towards the pole (only the linear axes' directions enter B).
//
// Sampled once, at load: at one tool length or the largest over several (volkins: the tool
// changes while it runs; the bound then holds between the smallest and the largest), at the
// model's temperatures or over their whole ranges (volkins: they change while it runs).
#pragma once

#include <array>
#include <vector>

#include "vc/machine/forward.hpp"
#include "vc/machine/model.hpp"

namespace vc::machine {

class ContractionBound {
 public:
  static constexpr int kBands = 4;

  // `over_temperatures`: each sample at temperatures drawn within every input's range (else
  // at their current values).
  ContractionBound(const Model& model, const std::vector<double>& tool_lengths_mm, bool over_temperatures = false);

  // kappa in a band (band_of); infinity where the samples cannot bound it.
  double kappa(int band) const { return kappa_[static_cast<std::size_t>(band)]; }
  // kappa of the position's equations alone (rotary joints held); infinity where not sampled.
  double position_kappa() const { return position_kappa_; }
  // kappa of the full correction's equations at a pole angle: its band's above full correction,
  // else the fade band's (kappa sin(phi) as sampled, over sin(phi); infinity below the sampled
  // band or where it was not sampled).
  double full_kappa(double pole_angle_rad) const {
    const int band = band_of(pole_angle_rad);
    return band >= 0 ? kappa(band) : fade_band_kappa(pole_angle_rad);
  }
  // The band of a pole angle, -1 below full correction.
  int band_of(double pole_angle_rad) const;
  // The band of the pole angle at an ideal pose and its derivatives, without atan2 (the same
  // as band_of(pole_angle_at(...))).
  int band_at(const ToolPose& ideal, const PoseDerivatives& d) const;
  // Whether the bound was sampled for this tool length (within the sampled ones' range).
  bool covers(double tool_length_mm) const { return tool_length_mm >= shortest_mm_ && tool_length_mm <= longest_mm_; }

 private:
  // The largest contraction per band at one tool length over the travel, and the position's
  // alone (machines with rotary joints); counts the samples.
  struct Largest {
    std::array<double, kBands> band{};
    std::array<int, kBands> count{};
    double position = 0.0;
    int position_count = 0;
    double fade_band = 0.0;  // kappa sin(phi)
    int fade_band_count = 0;
  };
  Largest sample(const Model& model, double tool_length_mm, bool over_temperatures) const;
  double fade_band_kappa(double pole_angle_rad) const;

  bool affine_;  // three linear axes: one band
  double full_rad_;
  double fade_start_rad_;               // the fade band sampled: [fade_start_rad_, full_rad_)
  std::array<int, kMaxAxes> rotary_{};  // the rotary joints
  int rotary_count_ = 0;
  std::array<double, kBands> edge_cos_{}, edge_sin_{};  // of the bands' lower edges
  std::array<double, kBands> kappa_{};
  double position_kappa_;
  double fade_band_kappa_sin_;  // kappa sin(phi) in the fade band
  double shortest_mm_ = 0.0, longest_mm_ = -1.0;
};

}  // namespace vc::machine
