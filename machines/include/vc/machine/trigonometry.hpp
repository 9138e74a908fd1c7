// Trigonometry of the servo thread's chain walks: the sines and cosines of error angles (small,
// radians) and of rotary joint positions (degrees), and the rotations R(a, b, c) of model.md.
// Real-time: no allocation; within an ulp or two of the exact values.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

#include "vc/tables/units.hpp"

namespace vc::machine {

// sin and cos of x; within an ulp of std::sin / std::cos, fast for the small angles of
// error tables.
inline void sin_cos(double x, double& s, double& c) noexcept {
  if (std::abs(x) < 1e-3) {
    // Taylor series; the first omitted terms (x^7 / 5040, x^8 / 40320) are below half an ulp
    // of the result for |x| < 1e-3 rad (206 arcsec). Multiplying by the rounded reciprocals
    // (not dividing: a division is several times slower, and this runs three times per axis
    // per chain walk) moves the small terms by ~1e-16 of themselves, far below an ulp of 1.
    constexpr double k6 = 1.0 / 6.0, k12 = 1.0 / 12.0, k20 = 1.0 / 20.0, k30 = 1.0 / 30.0;
    const double x2 = x * x;
    s = x * (1.0 - x2 * k6 * (1.0 - x2 * k20));
    c = 1.0 - x2 * 0.5 * (1.0 - x2 * k12 * (1.0 - x2 * k30));
    return;
  }
  s = std::sin(x);
  c = std::cos(x);
}

// sin and cos of `deg` degrees (a rotary joint's position), within 2.2e-16 (2 ulp of 1) of the
// exact values. The angle is reduced to r in [-45, 45] deg by the nearest multiple of 90, exactly
// (90 k is exact and so is deg - 90 k: Sterbenz), then sin and cos of r are Taylor series up to
// x^17 and x^18 (the first omitted terms are below 1e-19 for |x| <= pi / 4). In degrees the quarter
// turns are exact (sin 180 deg = 0, not the 1.2e-16 of std::sin(pi)). Not libm's sincos: it takes
// ~75 instructions and 21 code cache lines here, this ~47 and ~8, for every rotary joint of every
// pose the servo cycle evaluates (15 in a contour cycle on the MC-300).
inline void sin_cos_deg(double deg, double& s, double& c) noexcept {
  if (!(std::abs(deg) <= 1e12)) {  // far outside any travel (or not finite): libm's answer
    s = std::sin(deg * tables::kDegToRad);
    c = std::cos(deg * tables::kDegToRad);
    return;
  }
  constexpr double kRound = 0x1.8p52;  // adding and subtracting it rounds to the nearest integer
  const double quarters = (deg * (1.0 / 90.0) + kRound) - kRound;
  const double x = (deg - 90.0 * quarters) * tables::kDegToRad;
  const double z = x * x;
  constexpr double f3 = 1.0 / 6, f5 = f3 / 20, f7 = f5 / 42, f9 = f7 / 72, f11 = f9 / 110, f13 = f11 / 156,
                   f15 = f13 / 210, f17 = f15 / 272;  // 1 / n!
  constexpr double f2 = 1.0 / 2, f4 = f2 / 12, f6 = f4 / 30, f8 = f6 / 56, f10 = f8 / 90, f12 = f10 / 132,
                   f14 = f12 / 182, f16 = f14 / 240, f18 = f16 / 306;
  const double sr = x - x * z * (f3 - z * (f5 - z * (f7 - z * (f9 - z * (f11 - z * (f13 - z * (f15 - z * f17)))))));
  const double cr =
      1.0 - z * (f2 - z * (f4 - z * (f6 - z * (f8 - z * (f10 - z * (f12 - z * (f14 - z * (f16 - z * f18))))))));
  switch (static_cast<std::int64_t>(quarters) & 3) {  // deg = 90 quarters + r
    case 0:
      s = sr;
      c = cr;
      break;
    case 1:
      s = cr;
      c = -sr;
      break;
    case 2:
      s = -sr;
      c = -cr;
      break;
    default:
      s = -cr;
      c = sr;
      break;
  }
}

// R(a, b, c) = Rx(a) * Ry(b) * Rz(c) (model.md), exact trigonometry, from the sines and
// cosines of a, b, c.
inline void rotation_xyz(double sa, double ca, double sb, double cb, double sc, double cc,
                         Eigen::Matrix3d& r) noexcept {
  r << cb * cc, -cb * sc, sb, ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -sa * cb, sa * sc - ca * sb * cc,
      sa * cc + ca * sb * sc, ca * cb;
}

// R(a, b, c).
inline Eigen::Matrix3d rotation_xyz(const Eigen::Vector3d& abc) noexcept {
  double sa, ca, sb, cb, sc, cc;
  sin_cos(abc[0], sa, ca);
  sin_cos(abc[1], sb, cb);
  sin_cos(abc[2], sc, cc);
  Eigen::Matrix3d r;
  rotation_xyz(sa, ca, sb, cb, sc, cc, r);
  return r;
}

// R(a, b, c) and its angular velocity per unit change of (a, b, c), as matrix columns:
// omega = a' e_x + b' Rx(a) e_y + c' Rx(a) Ry(b) e_z.
inline void rotation_xyz(const Eigen::Vector3d& abc, Eigen::Matrix3d& r, Eigen::Matrix3d& rate) noexcept {
  double sa, ca, sb, cb, sc, cc;
  sin_cos(abc[0], sa, ca);
  sin_cos(abc[1], sb, cb);
  sin_cos(abc[2], sc, cc);
  rotation_xyz(sa, ca, sb, cb, sc, cc, r);
  rate << 1.0, 0.0, sb, 0.0, ca, -sa * cb, 0.0, sa, ca * cb;
}

}  // namespace vc::machine
