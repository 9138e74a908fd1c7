// How far LinuxCNC's straight interpolation between two corrected points can stray from the
// exact correction, bounded without evaluating the correction in between, so that the path
// corrector can accept short pieces unchecked.
//
// Between nominal joints a and b (world = joints), LinuxCNC runs the corrected joints
// c(t) = C(a) + t (C(b) - C(a)); the exact correction is C(n(t)) = n(t) + d(n(t)). Their
// difference is the error of interpolating the correction d linearly, mapped to the tool tip
// by the Jacobian J. Two bounds of it:
//   slope:     |J d'| <= k_j per unit of joint j          ->  sum_j k_j |b_j - a_j| / 2
//   curvature: |J d_ij''| <= M_ij where d is smooth       ->  sum_ij M_ij |b_i - a_i| |b_j - a_j| / 8
// d is smooth except where a table interpolated linearly changes cells, or where any table
// meets its grid ends (it holds its end value outside). Tables are read at the corrected
// joints, so these kinks lie where a corrected joint crosses a node: the curvature bound
// holds only for pieces whose corrected joints stay clear of every node (by 1e-3 mm or deg,
// far more than c(t) strays from the straight line between the corrected ends when the
// bound passes), and is infinite otherwise. The slope bound holds across kinks. k and M are
// the largest values found at 150 points spread over the travel and 150 in the pole fade
// band, where the orientation correction fades in (finite differences of the
// core's correction; curvature stencils that come near a kink are left out), per tool
// length, doubled for what the sampling may miss. The same bounds for the tool direction
// (rad), with the direction's Jacobian in place of the tip's.
#pragma once

#include <Eigen/Core>
#include <array>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::predistort {

class CorrectionBounds {
 public:
  // The sampling of a tool length shared by correctors that run at once (one per thread):
  // the samples are split in parts, each sampled by a corrector that needs the result and
  // finds the part not yet taken; all get the same result as one that sampled alone.
  class Shared;

  CorrectionBounds(const machine::Model& model, const machine::Conditions& conditions, Shared* shared = nullptr);

  // Bounds of the interpolation error between nominal joints a and b, at the tool tip (mm)
  // and in the tool direction (rad).
  struct Bound {
    double mm, rad;
  };
  Bound slope_bound(const machine::Joints& a, const machine::Joints& b, double tool_length_mm);
  // Also given the corrected joints at a and b.
  Bound curvature_bound(const machine::Joints& a, const machine::Joints& b, const machine::Joints& corrected_a,
                        const machine::Joints& corrected_b, double tool_length_mm);

  // True if a node of a table lies within the margin of the corrected joints' way from a to b.
  bool crosses_kink(const machine::Joints& corrected_a, const machine::Joints& corrected_b) const;

 private:
  using PerJoint = Eigen::Matrix<double, machine::kMaxAxes, machine::kMaxAxes>;
  struct Sampled {
    double tool_length_mm;
    std::array<double, machine::kMaxAxes> slope;      // k_j
    PerJoint curvature;                               // M_ij
    std::array<double, machine::kMaxAxes> slope_rad;  // the same for the tool direction
    PerJoint curvature_rad;
  };
  // Kinks along one joint from one grid variable: node positions (all nodes of a linear
  // table, the ends of a cubic one), repeating every `period` deg on a periodic grid.
  struct Kinks {
    double period;           // 0 if not periodic
    std::vector<double> at;  // sorted
    // The answer of the last search: the first node after the last interval asked about.
    // Pieces come along a path, so the next search mostly ends there again.
    mutable std::size_t hint = 0;
    std::size_t first_after(double x) const;  // index of the first node > x (at.size() if none)
  };
  static constexpr int kParts = 2;
  const Sampled& sampled(double tool_length_mm);
  // Largest slopes and curvatures (without the margin) at samples part, part + kParts, ...
  Sampled sample_part(double tool_length_mm, int part) const;
  static void merge(Sampled& into, const Sampled& part);
  bool kink_near(int joint, double x0, double x1, double margin) const;

  const machine::Model& model_;
  machine::Conditions conditions_;
  Shared* shared_;
  std::array<std::vector<Kinks>, machine::kMaxAxes> kinks_;  // per joint
  std::vector<Sampled> sampled_;
};

class CorrectionBounds::Shared {
 private:
  friend class CorrectionBounds;
  // Takes parts of the tool length's sampling while some are left (sampled by `bounds`),
  // then waits for the parts others took.
  Sampled sampled(const CorrectionBounds& bounds, double tool_length_mm);

  struct Entry {
    double tool_length_mm;
    int taken = 0, done = 0;
    Sampled result{};
    std::exception_ptr error{};
  };
  std::mutex mutex_;
  std::condition_variable finished_;
  std::deque<Entry> entries_;
};

}  // namespace vc::predistort
