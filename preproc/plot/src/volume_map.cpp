#include "vc/plot/volume_map.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "plot_format.hpp"
#include "vc/fit_tables/evaluate.hpp"
#include "vc/fit_tables/study.hpp"
#include "vc/machine/forward.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::plot {
namespace {

using fit_tables::Pose;

// `count` positions from `low` to `high`, both ends included (one: the middle).
std::vector<double> spaced(double low, double high, int count) {
  if (count == 1) return {(low + high) / 2};
  std::vector<double> v;
  for (int k = 0; k < count; ++k) v.push_back(low + (high - low) * k / (count - 1));
  return v;
}

// Where a rotary axis is tried when looking for its worst position: every multiple of 15 deg
// in its travel (at most one turn: a full turn's end is its start) and the travel's ends, so
// that the worst position found is one an operator can type.
std::vector<double> rotary_candidates(const machine::Axis& axis) {
  const double low = axis.travel_min, high = std::min(axis.travel_max, axis.travel_min + 360.0);
  const bool full_turn = axis.travel_max - axis.travel_min >= 360.0 - 1e-9;
  std::vector<double> v{low};
  for (double a = std::ceil(low / 15.0) * 15.0; a < high - 1e-9; a += 15.0)
    if (a > low + 1e-9) v.push_back(a);
  if (!full_turn) v.push_back(high);
  return v;
}

std::string rotary_label(const machine::Model& model, const machine::Joints& q) {
  std::string label;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary)
      label += (label.empty() ? "" : ", ") + std::string(1, model.axes[static_cast<std::size_t>(j)].letter) + " " +
               number(q[j]) + " deg";
  return label.empty() ? "no rotary axes" : label;
}

double tip_error_um(const machine::Model& model, const machine::Joints& q, double tool_length_mm) {
  return machine::volumetric_error(model, q, tool_length_mm).position_mm.norm() * 1e3;
}

// The rotary setting whose largest uncompensated |e| over the linear travel's corners and
// middles (3 positions per linear joint) is largest, at tool length L.
machine::Joints worst_rotary(const machine::Model& model, const std::vector<int>& linear,
                             const std::vector<int>& rotary, double tool_length_mm) {
  std::vector<std::vector<double>> candidates;
  for (const int j : rotary) candidates.push_back(rotary_candidates(model.axes[static_cast<std::size_t>(j)]));
  machine::Joints q = machine::Joints::Zero(model.joint_count()), worst = q;
  double worst_um = -1.0;
  std::vector<std::size_t> r(rotary.size(), 0);
  for (bool more = true; more;) {
    for (std::size_t k = 0; k < rotary.size(); ++k) q[rotary[k]] = candidates[k][r[k]];
    double largest = 0.0;
    std::vector<int> l(linear.size(), 0);
    for (bool more_linear = true; more_linear;) {
      for (std::size_t k = 0; k < linear.size(); ++k) {
        const machine::Axis& a = model.axes[static_cast<std::size_t>(linear[k])];
        q[linear[k]] = a.travel_min + (a.travel_max - a.travel_min) * l[k] / 2.0;
      }
      largest = std::max(largest, tip_error_um(model, q, tool_length_mm));
      more_linear = false;
      for (std::size_t k = 0; k < linear.size() && !more_linear; ++k) {
        if (++l[k] < 3)
          more_linear = true;
        else
          l[k] = 0;
      }
    }
    if (largest > worst_um) {
      worst_um = largest;
      worst = q;
    }
    more = false;
    for (std::size_t k = 0; k < rotary.size() && !more; ++k) {
      if (++r[k] < candidates[k].size())
        more = true;
      else
        r[k] = 0;
    }
  }
  return worst;
}

}  // namespace

VolumeMap volume_map(const machine::Model& model, const VolumeMapOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.grid < 2 || options.grid > 101) throw std::invalid_argument("the volume map's grid is 2..101 positions");
  if (options.levels < 1 || options.levels > 7) throw std::invalid_argument("the volume map has 1..7 levels");
  std::vector<double> lengths = options.tool_lengths_mm;
  if (lengths.empty()) lengths.push_back(model.tool_length_mm);
  for (const double l : lengths)
    if (!std::isfinite(l) || l < 0) throw std::invalid_argument("tool lengths must be numbers >= 0 mm");
  std::sort(lengths.begin(), lengths.end());
  lengths.erase(std::unique(lengths.begin(), lengths.end()), lengths.end());

  std::vector<int> linear, rotary;
  for (int j = 0; j < model.joint_count(); ++j)
    (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Linear ? linear : rotary).push_back(j);
  if (linear.size() < 3)
    throw std::invalid_argument(model.info.name + " has " + std::to_string(linear.size()) +
                                " linear axes: the volume map needs three");

  VolumeMap map;
  map.machine_name = model.info.name;
  map.machine_path = model.path;
  map.first_joint = linear[0];
  map.second_joint = linear[1];
  map.level_joint = linear[2];
  if (!options.plane.empty()) {
    std::string names;
    for (const int j : linear)
      names +=
          static_cast<char>(std::tolower(static_cast<unsigned char>(model.axes[static_cast<std::size_t>(j)].letter)));
    const auto joint_of = [&](char letter) {
      const std::size_t at = names.find(static_cast<char>(std::tolower(static_cast<unsigned char>(letter))));
      return at == std::string::npos ? -1 : linear[at];
    };
    const int first = options.plane.size() == 2 ? joint_of(options.plane[0]) : -1;
    const int second = options.plane.size() == 2 ? joint_of(options.plane[1]) : -1;
    if (first < 0 || second < 0 || first == second || linear.size() != 3)
      throw std::invalid_argument("the volume map's plane '" + options.plane + "' is not two of " + model.info.name +
                                  "'s linear axes (" + names + ")" +
                                  (linear.size() != 3 ? ": a plane is chosen on machines with three linear axes" : ""));
    map.first_joint = first;
    map.second_joint = second;
    for (const int j : linear)
      if (j != first && j != second) map.level_joint = j;
  }
  const auto travel = [&](int joint, int count) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(joint)];
    return spaced(a.travel_min, a.travel_max, count);
  };
  map.first_mm = travel(map.first_joint, options.grid);
  map.second_mm = travel(map.second_joint, options.grid);
  map.levels_mm = travel(map.level_joint, options.levels);
  map.compensations = {"none"};

  // The stock controller's tables, fitted over the map's tool lengths (the tables cannot know
  // which tool is in the spindle): judged on the map's poses below, never fitted on them.
  std::optional<fit_tables::Study> study;
  if (!options.controller.empty()) {
    const fit_tables::Controller controller =
        fit_tables::load_controller(fit_tables::controller_file(options.controller));
    fit_tables::StudyOptions o;
    o.tool_lengths_mm = lengths;
    o.check_tool_lengths_mm = std::vector<double>{};  // only the map's tool lengths are judged, here
    o.fresh_poses = options.fresh_poses;
    study = fit_tables::run_study(model, controller, o);
    map.controller_title = controller.title.empty() ? controller.name : controller.title;
    map.compensations.push_back("usual practice");
    map.compensations.push_back("modified method");
  }

  std::vector<Pose> all_poses;
  for (const double length : lengths) {
    std::vector<RotarySetting> settings;
    RotarySetting zero{"", false, machine::Joints::Zero(model.joint_count())};
    zero.label = rotary_label(model, zero.q);
    settings.push_back(zero);
    if (!rotary.empty()) {
      RotarySetting worst{"", true, worst_rotary(model, linear, rotary, length)};
      for (const int j : linear) worst.q[j] = 0.0;
      worst.label = rotary_label(model, worst.q);
      // At 0 already the worst: one sheet says it all.
      if ((worst.q - zero.q).norm() > 0)
        settings.push_back(worst);
      else
        settings.front().label += " (also the worst position)";
    }
    for (const RotarySetting& setting : settings) {
      MapSheet sheet;
      sheet.tool_length_mm = length;
      sheet.rotary = setting;
      std::vector<Pose> poses;
      for (const double level : map.levels_mm)
        for (const double second : map.second_mm)
          for (const double first : map.first_mm) {
            Pose p{setting.q, length};
            p.q[map.first_joint] = first;
            p.q[map.second_joint] = second;
            p.q[map.level_joint] = level;
            poses.push_back(p);
          }
      std::vector<std::vector<double>> by_compensation{fit_tables::uncompensated_errors(model, poses)};
      if (study) {
        by_compensation.push_back(fit_tables::table_errors(model, study->set, study->usual, poses));
        by_compensation.push_back(fit_tables::table_errors(model, study->set, study->modified, poses));
      }
      const std::size_t per_level = map.first_mm.size() * map.second_mm.size();
      for (const std::vector<double>& errors : by_compensation) {
        std::vector<std::vector<double>> levels;
        for (std::size_t l = 0; l < map.levels_mm.size(); ++l)
          levels.emplace_back(errors.begin() + static_cast<std::ptrdiff_t>(l * per_level),
                              errors.begin() + static_cast<std::ptrdiff_t>((l + 1) * per_level));
        sheet.error_um.push_back(std::move(levels));
        sheet.max_um.push_back(*std::max_element(errors.begin(), errors.end()));
      }
      all_poses.insert(all_poses.end(), poses.begin(), poses.end());
      map.sheets.push_back(std::move(sheet));
    }
  }
  map.poses = static_cast<int>(all_poses.size());
  const std::vector<double> full = fit_tables::full_correction_errors(model, model, all_poses);
  map.full_correction_max_um = *std::max_element(full.begin(), full.end());
  map.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return map;
}

std::string full_correction_statement(const VolumeMap& map) {
  // Up to the Newton solver's tolerance (1e-10 mm): what is printed is what was computed.
  return "volkins: 0 on the model; what remains is measurement uncertainty (full correction: largest |e| " +
         scientific_text(map.full_correction_max_um, 1) + " um over the map's " + std::to_string(map.poses) + " poses)";
}

}  // namespace vc::plot
