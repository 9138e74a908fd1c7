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

Eigen::Matrix3d rotation_xyz(const Eigen::Vector3d& abc) {
  const double sa = std::sin(abc[0]), ca = std::cos(abc[0]);
  const double sb = std::sin(abc[1]), cb = std::cos(abc[1]);
  const double sc = std::sin(abc[2]), cc = std::cos(abc[2]);
  Eigen::Matrix3d r;
  r << cb * cc, -cb * sc, sb,
       ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -sa * cb,
       sa * sc - ca * sb * cc, sa * cc + ca * sb * sc, ca * cb;
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
