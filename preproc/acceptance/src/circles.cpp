#include "vc/acceptance/circles.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "vc/tables/number_text.hpp"

namespace vc::acceptance {
namespace {

int axis_index(char letter) { return letter == 'X' ? 0 : letter == 'Y' ? 1 : 2; }

}  // namespace

int Circle::first() const { return axis_index(plane[0]); }
int Circle::second() const { return axis_index(plane[1]); }

Eigen::Vector3d Circle::at(double angle_rad) const {
  Eigen::Vector3d p = centre_mm;
  p[first()] += radius_mm * std::cos(angle_rad);
  p[second()] += radius_mm * std::sin(angle_rad);
  return p;
}

std::vector<Circle> plan_circles(const WorkVolume& volume, const std::string& planes, double radius_mm) {
  std::vector<Circle> out;
  if (planes == "none") return out;
  if (!(radius_mm >= 0)) throw std::runtime_error("--circle-radius must be > 0 mm (0: the longest standard ballbar that fits)");
  std::istringstream list(planes);
  for (std::string plane; std::getline(list, plane, ',');) {
    if (plane != "XY" && plane != "YZ" && plane != "ZX")
      throw std::runtime_error("--circles " + planes + ": XY, YZ and ZX, separated by commas, or none");
    for (const Circle& c : out)
      if (c.plane == plane) throw std::runtime_error("--circles " + planes + ": " + plane + " twice");
    Circle c;
    c.name = "circle-" + plane;
    c.plane = plane;
    c.centre_mm = volume.centre();
    const Eigen::Vector3d half = (volume.high_mm - volume.low_mm) / 2;
    const double room = std::min(half[c.first()], half[c.second()]);
    c.radius_mm = radius_mm;
    if (radius_mm == 0)
      for (double length : kBallbarLengthsMm)
        if (length <= room) c.radius_mm = length;
    if (c.radius_mm == 0)
      throw std::runtime_error(c.name + ": no standard ballbar (50 mm or longer) fits in the volume's " +
                               fixed_text(2 * room, 3) + " mm in " + plane + ": a larger --volume or --circles none");
    if (c.radius_mm > room + 1e-9)
      throw std::runtime_error(c.name + ": the radius " + number_text(c.radius_mm) + " mm leaves the volume (" +
                               fixed_text(room, 3) + " mm from its centre in " + plane + ")");
    out.push_back(c);
  }
  if (out.empty()) throw std::runtime_error("--circles: XY, YZ and ZX, separated by commas, or none");
  return out;
}

}  // namespace vc::acceptance
