#include "vc/shop/local_fit.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Dense>

namespace vc::shop {
namespace {

using Vector5d = Eigen::Matrix<double, 5, 1>;

// An anchor's equation row in (v, w_x, w_y).
Vector5d row_of(const Anchor& a) {
  Vector5d row;
  row << a.normal, -a.height_mm * a.normal.y(), a.height_mm * a.normal.x();  // h (e_z x n)
  return row;
}

// Gaussian weight of an anchor at the point (0 beyond the radius or the angle).
double weight_of(const Anchor& a, const Eigen::Vector3d& tip, const Eigen::Matrix3d& frame,
                 const LocalFitOptions& options) {
  const double d = (a.at - tip).norm() / options.radius_mm;
  if (d > 1) return 0;
  double exponent = d * d;
  if (options.angle_rad > 0) {
    const double cosine = std::clamp(((a.frame.transpose() * frame).trace() - 1) / 2, -1.0, 1.0);
    const double turn = std::acos(cosine) / options.angle_rad;
    if (turn > 1) return 0;
    exponent += turn * turn;
  }
  return std::exp(-2 * exponent);  // sigma = half the radius, half the angle
}

// z^2 of the estimated tilt components (the last k of x) against their covariance: the
// weighted least squares' sandwich, the several cuts of one point summed into one term.
double tilt_significance(const std::vector<Anchor>& anchors, const std::vector<std::pair<int, double>>& used,
                         const Eigen::Matrix<double, 2, Eigen::Dynamic>& seen, const Eigen::MatrixXd& normal_matrix,
                         const Eigen::VectorXd& x, double noise_mm) {
  const auto n = x.size(), k = seen.cols();
  const Eigen::VectorXd tilt = x.tail(k);
  if (!(noise_mm > 0)) return tilt.isZero(0) ? 0.0 : 1e300;
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd point_sum = Eigen::VectorXd::Zero(n);
  for (std::size_t i = 0; i < used.size(); ++i) {
    const Anchor& a = anchors[static_cast<std::size_t>(used[i].first)];
    const Vector5d row = row_of(a);
    Eigen::VectorXd reduced(n);
    reduced << row.head<3>(), seen.transpose() * row.tail<2>();
    point_sum += used[i].second * reduced;
    const bool last_of_point =
        i + 1 == used.size() || anchors[static_cast<std::size_t>(used[i + 1].first)].point != a.point;
    if (last_of_point) {
      meat += point_sum * point_sum.transpose();
      point_sum.setZero();
    }
  }
  const Eigen::MatrixXd inverse = normal_matrix.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
  const Eigen::MatrixXd covariance = noise_mm * noise_mm * inverse * meat * inverse;
  return tilt.dot(covariance.bottomRightCorner(k, k).ldlt().solve(tilt));
}

// v from its normal equations, in the directions the normals see: those with less than 1 %
// of the weight (normals within some 6 deg of a plane) stay at zero. Normals spread by a few
// degrees (the cuts of one pass next to a point, their tool frames turned by a few degrees
// of C) do not tell a shift along the surface; a least-squares answer there is noise, tens
// of um along the path.
Eigen::Vector3d seen_shift(const Eigen::Matrix3d& nvv, const Eigen::Vector3d& right, double weight) {
  constexpr double kSeenShare = 1e-2;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(nvv);
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const double lambda = eigen.eigenvalues()[i];
    if (lambda < kSeenShare * weight) continue;
    const Eigen::Vector3d e = eigen.eigenvectors().col(i);
    v += e * (e.dot(right) / lambda);
  }
  return v;
}

}  // namespace

LocalFit fit_tool_displacement(const std::vector<Anchor>& anchors, const Eigen::Vector3d& tip,
                               const Eigen::Matrix3d& frame, const LocalFitOptions& options) {
  using Matrix5d = Eigen::Matrix<double, 5, 5>;
  // Normal equations in (v, w_x, w_y).
  Matrix5d normal_matrix = Matrix5d::Zero();
  Vector5d right = Vector5d::Zero();
  double weight = 0, point_weights_squared = 0;  // the points' weights: their cuts' summed
  double point_weight = 0;
  int point = -1;
  std::vector<std::pair<int, double>> used;  // anchors within reach, their weights
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    const double w = weight_of(anchors[i], tip, frame, options);
    if (w <= 0) continue;
    const Vector5d row = row_of(anchors[i]);
    normal_matrix += w * row * row.transpose();
    right += w * (anchors[i].deviation_mm - row.tail<2>().dot(options.known_tilt_rad.head<2>())) * row;
    weight += w;
    if (anchors[i].point != point) {  // a point's cuts stand together
      point_weights_squared += point_weight * point_weight;
      point_weight = 0;
      point = anchors[i].point;
    }
    point_weight += w;
    if (options.with_tilt) used.emplace_back(static_cast<int>(i), w);
  }
  LocalFit fit;
  fit.covered = weight > 1e-6;
  if (!fit.covered) return fit;
  point_weights_squared += point_weight * point_weight;
  fit.support = weight * weight / point_weights_squared;
  // (For the tilt's fit, a small ridge keeps the directions of v no normal sees at zero.)
  const Eigen::Matrix3d nvv = normal_matrix.topLeftCorner<3, 3>() + 1e-6 * weight * Eigen::Matrix3d::Identity();
  const auto nvv_solver = nvv.ldlt();
  fit.shift_mm = seen_shift(normal_matrix.topLeftCorner<3, 3>(), right.head<3>(), weight);
  if (!options.with_tilt) return fit;
  // What the points say about w once v has taken what it can: the Schur complement. Its
  // eigenvalues are (weight x) the heights' spread squared in each direction of w.
  const Eigen::Matrix<double, 3, 2> nvw = normal_matrix.topRightCorner<3, 2>();
  const Eigen::Matrix2d schur = normal_matrix.bottomRightCorner<2, 2>() - nvw.transpose() * nvv_solver.solve(nvw);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(schur);
  Eigen::Matrix<double, 2, Eigen::Dynamic> seen(2, 0);
  for (int i = 0; i < 2; ++i)
    if (eigen.eigenvalues()[i] >= options.min_spread_mm * options.min_spread_mm * weight) {
      seen.conservativeResize(Eigen::NoChange, seen.cols() + 1);
      seen.col(seen.cols() - 1) = eigen.eigenvectors().col(i);
    }
  if (seen.cols() == 0) {
    fit.tilt = TiltFit::Unseen;
    return fit;
  }
  // v and the seen components of w.
  const auto k = seen.cols(), n = 3 + k;
  Eigen::MatrixXd reduced(n, n);
  Eigen::VectorXd reduced_right(n);
  reduced.topLeftCorner(3, 3) = nvv;
  reduced.topRightCorner(3, k) = nvw * seen;
  reduced.bottomLeftCorner(k, 3) = (nvw * seen).transpose();
  reduced.bottomRightCorner(k, k) = seen.transpose() * normal_matrix.bottomRightCorner<2, 2>() * seen;
  reduced_right << right.head<3>(), seen.transpose() * right.tail<2>();
  const Eigen::VectorXd x = reduced.ldlt().solve(reduced_right);
  // Kept where it stands above its noise (z^2 > k), shrunk by the share of its size that is
  // not noise, 1 - k / z^2 (the empirical Wiener factor): a tilt that is mostly noise would
  // put that noise on the part.
  const double z2 = tilt_significance(anchors, used, seen, reduced, x, options.noise_mm);
  if (z2 <= static_cast<double>(k)) {
    fit.tilt = TiltFit::BelowNoise;
    return fit;
  }
  fit.tilt = TiltFit::Estimated;
  fit.tilt_components = static_cast<int>(k);
  fit.shift_mm = x.head<3>();
  fit.tilt_rad.head<2>() = (1 - static_cast<double>(k) / z2) * (seen * x.tail(k));
  return fit;
}

}  // namespace vc::shop
