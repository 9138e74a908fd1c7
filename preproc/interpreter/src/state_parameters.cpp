// The interpreter's state as LinuxCNC 2.9's read-only parameters show it (interp_namedparams.cc
// lookup_named_param, #5400 and #5420-#5428): in program units, as the program sees them. What
// a program cannot know offline (the task, overrides, probe results, the tool in the spindle
// before the program's first M6 or M61) is not given, and a line that reads it is refused.
#include "words.hpp"

namespace vc::interpreter {

std::optional<double> Interpreter::StateView::numbered(int n) const {
  const Interpreter& i = interpreter;
  if (n == 5400) return i.tool_in_spindle_ >= 0 ? std::optional<double>(i.tool_in_spindle_) : std::nullopt;
  if (n > 5400 && n <= 5413) return i.spindle_tool_parameter(n);
  if (n < 5420 || n > 5428) return std::nullopt;
  // LinuxCNC refuses the position while cutter compensation offsets it.
  if (i.compensation_.offsets() && !i.compensation_.first_move()) return std::nullopt;
  if (n > 5425) return 0.0;  // U V W: none
  const int axis = n - 5420;
  if (!(i.known_ >> axis & 1u)) return std::nullopt;  // not set yet (the machine's start is unknown)
  return i.position_[static_cast<std::size_t>(axis)] / (is_linear(axis) && i.inches_ ? kInch : 1.0);
}

std::optional<double> Interpreter::spindle_tool_parameter(int n) const {
  // #5401-#5413 (rs274ngc_pre.cc set_tool_parameters): the tool table entry of the tool in the
  // spindle as it is now (G10 L1 changes it), in the machine's units: X..W offsets, diameter,
  // front and back angle, orientation. An empty spindle (tool 0) reads zeros.
  if (tool_in_spindle_ < 0 || !tool_data_known_) return std::nullopt;  // before M6: whatever the machine holds
  if (tool_in_spindle_ == 0) return 0.0;
  if (!tools_) return std::nullopt;
  const auto it = tools_->find(tool_in_spindle_);
  if (it == tools_->end()) return std::nullopt;
  const Tool& tool = it->second;
  if (n <= 5409) {
    const int axis = n - 5401;
    const bool angle = axis >= 3 && axis <= 5;
    return tool.offset[static_cast<std::size_t>(axis)] / (angle ? 1.0 : setup_.machine_unit_mm);
  }
  if (n == 5410) return tool.diameter / setup_.machine_unit_mm;
  if (n == 5411) return tool.front_angle;
  if (n == 5412) return tool.back_angle;
  return tool.orientation;
}

std::optional<double> Interpreter::StateView::named(const std::string& name) const {
  const Interpreter& i = interpreter;
  if (name.size() < 2 || name[0] != '_') return std::nullopt;
  const auto flag = [](bool b) { return std::optional<double>(b ? 1.0 : 0.0); };
  // Position: _x .. _c (program coordinates), _abs_x .. _abs_c (machine coordinates).
  const bool absolute = name.rfind("_abs_", 0) == 0;
  const std::string axis_name = absolute ? name.substr(5) : name.substr(1);
  if (axis_name.size() == 1) {
    const auto letter = std::string_view("xyzabc").find(axis_name[0]);
    if (letter == std::string_view::npos)
      return std::string_view("uvw").find(axis_name[0]) != std::string_view::npos ? std::optional<double>(0.0)
                                                                                  : std::nullopt;
    if (i.compensation_.offsets() && !i.compensation_.first_move()) return std::nullopt;
    const int axis = static_cast<int>(letter);
    if (!(i.known_ >> axis & 1u)) return std::nullopt;
    Position p = i.position_;
    if (absolute) {
      p = i.frame().world(p);
      if (!i.setup_.tool_length_in_world) p[2] += i.tool_offset_;  // LinuxCNC's world holds it
    }
    return p[static_cast<std::size_t>(axis)] / (is_linear(axis) && i.inches_ ? kInch : 1.0);
  }
  if (name == "_motion_mode") return i.motion_;
  if (name == "_plane") return i.plane_;
  if (name == "_ccomp")
    return i.compensation_.side() == CutterCompensation::kLeft    ? G_41
           : i.compensation_.side() == CutterCompensation::kRight ? G_42
                                                                  : G_40;
  if (name == "_metric") return flag(!i.inches_);
  if (name == "_imperial") return flag(i.inches_);
  if (name == "_absolute") return flag(!i.incremental_);
  if (name == "_incremental") return flag(i.incremental_);
  if (name == "_inverse_time") return flag(i.inverse_time_);
  if (name == "_units_per_minute") return flag(!i.inverse_time_);
  if (name == "_units_per_rev") return 0.0;
  if (name == "_coord_system")  // G54 .. G59.3
    return i.coordinate_system_ < 7 ? G_53 + 10 * i.coordinate_system_ : G_59_1 + i.coordinate_system_ - 7;
  if (name == "_tool_offset") return flag(i.tool_offset_ != 0.0);
  if (name == "_retract_r_plane") return flag(i.retract_to_r_);
  if (name == "_retract_old_z") return flag(!i.retract_to_r_);
  if (name == "_spindle_rpm_mode") return flag(!i.constant_surface_speed_);
  if (name == "_spindle_css_mode") return flag(i.constant_surface_speed_);
  if (name == "_feed_override") return flag(i.feed_override_);
  if (name == "_speed_override") return flag(i.spindle_override_);
  if (name == "_adaptive_feed") return flag(i.adaptive_feed_);
  if (name == "_feed_hold") return flag(i.feed_hold_);
  if (name == "_ijk_absolute_mode") return flag(i.arc_absolute_);
  if (name == "_lathe_diameter_mode") return 0.0;
  if (name == "_lathe_radius_mode") return 1.0;
  if (name == "_spindle_on") return flag(i.spindle_on_);
  if (name == "_spindle_cw") return flag(i.spindle_on_ && i.spindle_clockwise_);
  if (name == "_mist") return flag(i.mist_);
  if (name == "_flood") return flag(i.flood_);
  if (name == "_feed") return i.feed_;
  if (name == "_rpm") return std::abs(i.spindle_rpm_);
  if (name == "_current_tool") return numbered(5400);
  if (name == "_selected_tool") return i.selected_tool_ >= 0 ? std::optional<double>(i.selected_tool_) : std::nullopt;
  // LinuxCNC 2.9.0 (Debian 12's 2.9.0~pre1), whose rules this interpreter follows (the lathe
  // cycles are that release's; a program that tests for a later one is written for that one).
  if (name == "_vmajor") return 2.9;
  if (name == "_vminor") return 0.0;
  return std::nullopt;
}

}  // namespace vc::interpreter
