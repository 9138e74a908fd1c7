#include "vc/machine/model.hpp"

#include <cctype>
#include <cmath>

namespace vc::machine {

int Model::rotary_count() const {
  int n = 0;
  for (const Axis& a : axes) n += a.type == AxisType::Rotary;
  return n;
}

int Model::joint_of(char letter) const {
  for (int i = 0; i < joint_count(); ++i)
    if (axes[i].letter == letter) return i;
  return -1;
}

std::string Model::coordinates() const {
  std::string s;
  for (const Axis& a : axes) s += static_cast<char>(std::tolower(static_cast<unsigned char>(a.letter)));
  return s;
}

void sin_cos(double x, double& s, double& c) noexcept {
  if (std::abs(x) < 1e-3) {
    // Taylor series; the first omitted terms (x^7 / 5040, x^8 / 40320) are below half an ulp
    // of the result for |x| < 1e-3 rad (206 arcsec), so this equals std::sin / std::cos.
    const double x2 = x * x;
    s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0));
    c = 1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0));
    return;
  }
  s = std::sin(x);
  c = std::cos(x);
}

void rotation_xyz(const Eigen::Vector3d& abc, Eigen::Matrix3d& r, Eigen::Matrix3d& rate) noexcept {
  double sa, ca, sb, cb, sc, cc;
  sin_cos(abc[0], sa, ca);
  sin_cos(abc[1], sb, cb);
  sin_cos(abc[2], sc, cc);
  r << cb * cc, -cb * sc, sb,
       ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -sa * cb,
       sa * sc - ca * sb * cc, sa * cc + ca * sb * sc, ca * cb;
  rate << 1.0, 0.0, sb,
          0.0, ca, -sa * cb,
          0.0, sa, ca * cb;
}

Eigen::Matrix3d rotation_xyz(const Eigen::Vector3d& abc) noexcept {
  Eigen::Matrix3d r, rate;
  rotation_xyz(abc, r, rate);
  return r;
}

Eigen::Isometry3d line_placement(const Eigen::Vector3d& origin_mm, const Eigen::Vector3d& location_mm,
                                 const Eigen::Vector3d& location_rad) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = origin_mm + location_mm;
  t.linear() = rotation_xyz(location_rad);
  return t;
}

}  // namespace vc::machine
