// The surface a tool path leaves in the part: the material minus every volume the tool swept
// while cutting. The tool is a cylinder of the path's radius and `flute_length_mm` long,
// with a flat or a ball end; between two samples of a move it sweeps straight.
#pragma once

#include <optional>
#include <unordered_map>
#include <vector>

#include "vc/shop/tool_path.hpp"

namespace vc::shop {

struct SurfaceOptions {
  double flute_length_mm = 30.0;  // length of the tool that cuts, from the tip up
  double reach_mm = 0.5;          // deviations larger than this are not looked for
};

// Where a surface point was cut: the segment (samples [sample, sample + 1]) whose tool
// reaches deepest at it, and the fraction u along it.
struct Contact {
  int sample = 0;
  double u = 0.0;
  double depth_mm = 0.0;  // signed distance of the point to that tool (< 0: inside)
};

class MachinedSurface {
 public:
  // Keeps a reference to `path`, which must outlive it.
  MachinedSurface(const ToolPath& path, SurfaceOptions options = {});
  MachinedSurface(ToolPath&& path, SurfaceOptions options = {}) = delete;

  // Deviation of the machined surface from the nominal point p along the unit normal n (out
  // of the material), mm, + = material left: where the removed volume ends on the line
  // p + t n. Nothing if no cut reaches within reach_mm of p.
  std::optional<double> deviation(const Eigen::Vector3d& p, const Eigen::Vector3d& n) const;

  // The segments whose tools pass within `within_mm` of the deepest one at p (the deepest
  // first): the cuts that shaped the surface there. Empty if no cutting tool came within
  // reach_mm of p.
  std::vector<Contact> contacts(const Eigen::Vector3d& p, double within_mm) const;

  const ToolPath& path() const { return path_; }

 private:
  // min over segments of the tool's signed distance at p (< 0: inside the removed volume).
  double removed(const Eigen::Vector3d& p) const;
  double segment_distance(int i, const Eigen::Vector3d& p, double& u) const;
  long cell_key(const Eigen::Vector3d& p) const;

  const ToolPath& path_;
  SurfaceOptions options_;
  double cell_mm_ = 4.0;
  std::unordered_map<long, std::vector<int>> cells_;  // segments that can reach into each cell
};

}  // namespace vc::shop
