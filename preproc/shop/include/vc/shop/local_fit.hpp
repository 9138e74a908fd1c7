// The local strategy's estimate at one point of the program: how the tool stood off its
// nominal pose there, from the measured deviations near it (selftune_local.hpp).
//
// Each measured point k, at the cut that shaped it, gives one equation in the frame of that
// cut's tool (x, y square to the tool axis, z along it, tip into the spindle):
//     n_k . v + h_k (e_z x n_k) . w = deviation_k
// v: the tip's displacement; w: a small rotation of the tool axis about the tip (about x and
// y; one about the axis itself moves no surface a turning tool cuts); h_k: the point's
// position along the tool from the tip, so the tool's side at height h moves by v + w x h e_z.
// Least squares with gaussian weights: over the distance of the cut's tip (sigma = radius /
// 2, none beyond the radius) and over the turn between the cut's tool frame and the point's
// (sigma = angle / 2, none beyond the angle): a cut made at another pose of the rotary axes
// saw other errors of them.
//
// Why the tool frame: errors of a machine's linear axes, and of a table axis at one angle,
// stand still in it while a rotary table turns the part under the tool (a swarf pass with C
// turning 360 deg keeps the machine's linear axes nearly still); in the part frame they turn
// with the table. On a 3-axis or 3+2 program every cut has the same tool frame: the estimate
// of v and the weights are the part frame's.
//
// The rotation is estimated only where the points tell it from a shift of the tip: after
// taking out what v explains, their heights along the tool must still spread (weighted RMS)
// by `min_spread_mm` in the direction the rotation moves them. Floor points (normal along the
// tool) and points cut at one height see none of it; a swarf wall sees the tilt towards it and
// not the one along it (which moves no point of it): that component stays zero. And it is
// kept only where it stands above the noise, z^2 = w' C^-1 w > k (C: its covariance from
// `noise_mm` per measured point, the sandwich of the weighted least squares with the several
// cuts of a point counted as one point; k: the components seen), shrunk by 1 - k / z^2 (the
// share of its size that is not noise). Otherwise v is the fit without it.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace vc::shop {

// A measured deviation at the cut that shaped it.
struct Anchor {
  Eigen::Vector3d at;      // tool tip of the cut (part frame): for the distance
  Eigen::Vector3d normal;  // the point's normal in the cut's tool frame
  double height_mm = 0.0;  // the point's position along the cut's tool axis, from the tip
  double deviation_mm = 0.0;
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();  // the cut's tool frame in the part frame
  int point = 0;  // the measured point (one point may have several cuts, in a row)
};

enum class TiltFit {
  NotAsked,    // with_tilt false
  Unseen,      // the points' heights along the tool do not tell it from a shift
  BelowNoise,  // told apart, but not above the noise
  Estimated,
};

struct LocalFit {
  bool covered = false;                                // any measured cut within the radius and angle
  Eigen::Vector3d shift_mm = Eigen::Vector3d::Zero();  // v, tool frame
  Eigen::Vector3d tilt_rad = Eigen::Vector3d::Zero();  // w, tool frame (z = 0)
  TiltFit tilt = TiltFit::NotAsked;
  int tilt_components = 0;  // of w estimated (0, 1, 2)
  double support = 0.0;     // effective number of measured points in the fit, (sum W)^2 / sum W^2,
                            // W a point's weight (its cuts' summed): their noises are independent
};

struct LocalFitOptions {
  double radius_mm = 40.0;
  double angle_rad = 0.0;      // > 0: weights over the turn between tool frames, as above
  bool with_tilt = false;      // estimate w too (where the points tell it)
  double min_spread_mm = 1.0;  // heights' spread that tells a tilt from a shift
  double noise_mm = 0.0;       // standard deviation of a point's deviation (0: no noise test)
  Eigen::Vector3d known_tilt_rad = Eigen::Vector3d::Zero();  // w taken off the deviations first (not with_tilt)
};

// `frame`: the tool frame at the point (part frame).
LocalFit fit_tool_displacement(const std::vector<Anchor>& anchors, const Eigen::Vector3d& tip,
                               const Eigen::Matrix3d& frame, const LocalFitOptions& options);

}  // namespace vc::shop
