#include "vc/init/pivot_length.hpp"

#include <filesystem>

#include "vc/init/number.hpp"
#include "vc/init/pin_value.hpp"

namespace vc::init {
namespace {

const std::string kPin = "5axiskins.pivot-length";
constexpr double kModuleDefault = 250.0;  // 5axiskins.c's DEFAULT_PIVOT_LENGTH
constexpr double kGuiDefault = 250.0;     // 5axisgui's pivot_len, "to agree with default in 5axiskins.c"
const std::string kToolOffset = "motion.tooloffset.z";
const std::string kGuiPin = "5axisgui.pivot_len";

// Why a pivot length that does not follow the tool offset is refused, and how to net it.
const std::string kWhy =
    "with a pivot length that does not follow motion.tooloffset.z, G43 moves world Z only, which volkins' TCP world "
    "does not express (its world is the tool tip, the G43 offset below the spindle point along the tool); net it as "
    "LinuxCNC's bridgemill sample does: `loadrt sum2 names=pivotsum`, `addf pivotsum servo-thread`, `setp "
    "pivotsum.in0 PIVOT` (the mechanical pivot length), `net :tool-len motion.tooloffset.z => pivotsum.in1`, `net "
    ":pivot-len pivotsum.out => 5axiskins.pivot-length`";

struct Instance {
  std::string name;
  const HalCommand* loaded = nullptr;
};

// The instances `loadrt sum2` makes (a comp module): names=a,b, else count=N (sum2.0 ...
// sum2.N-1), else one, sum2.0.
std::vector<Instance> sum2_instances(const HalConfig& hal) {
  std::vector<Instance> instances;
  for (const HalCommand& c : hal.commands) {
    const auto load = loadrt_of(c);
    if (!load || load->module != "sum2") continue;
    std::string names;
    double count = 1.0;
    for (const std::string& a : load->arguments) {
      if (a.rfind("names=", 0) == 0) names = a.substr(6);
      if (a.rfind("count=", 0) == 0 && !parse_number(a.substr(6), count))
        throw LoadError(c.where(), "`" + a + "`: count= is not a number (rtapi_app would refuse it)");
    }
    if (!names.empty()) {
      for (std::size_t start = 0; start <= names.size();) {
        const std::size_t comma = std::min(names.find(',', start), names.size());
        instances.push_back({names.substr(start, comma - start), &c});
        start = comma + 1;
      }
    } else {
      for (int i = 0; i < static_cast<int>(count); ++i) instances.push_back({"sum2." + std::to_string(i), &c});
    }
  }
  return instances;
}

class Resolver {
 public:
  Resolver(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& k) : ini_(ini), hal_(hal), k_(k) {}

  PivotLength run() {
    const PinValue pivot = pin_value(hal_, kPin, kModuleDefault);
    if (pivot.source == PinValue::Source::Default)
      throw LoadError(
          pivot.net ? pivot.net->where() : k_.entry->where(),
          kPin +
              (pivot.net ? " is on signal " + pivot.signal + ", which no pin drives and no sets gives a value"
                         : std::string(" is netted nowhere in the HAL files read")) +
              ": it keeps 5axiskins' default 250, a constant: " + kWhy);
    if (pivot.source != PinValue::Source::Live)
      throw LoadError(pivot.command->where(),
                      kPin + " is the constant " + format_number(pivot.value) +
                          (pivot.source == PinValue::Source::Sets ? " (sets on its signal " + pivot.signal + ")" : "") +
                          ": " + kWhy);
    const Instance* sum = nullptr;
    const HalCommand* out_net = nullptr;
    for (const Instance& s : instances_) {
      std::string signal;
      if (const HalCommand* net = net_of_pin(hal_, s.name + ".out", &signal); net && signal == pivot.signal) {
        sum = &s;
        out_net = net;
      }
    }
    if (!sum)
      throw LoadError(pivot.net->where(), kPin + " follows " + pivot.driver + " at run time (signal " + pivot.signal +
                                              "), which is not the out of a sum2 loaded in the HAL files read: init "
                                              "follows the pivot length through a sum2 of the tool offset and a "
                                              "constant only; " +
                                              kWhy);
    const std::string& s = sum->name;
    PivotLength p;
    p.sum2 = s;

    // Which input is the tool offset: the one on the signal motion.tooloffset.z drives.
    std::string tool_signal;
    net_of_pin(hal_, kToolOffset, &tool_signal);
    const PinValue in[2] = {pin_value(hal_, s + ".in0", 0.0), pin_value(hal_, s + ".in1", 0.0)};
    bool on_tool[2];
    for (int i = 0; i < 2; ++i)
      on_tool[i] = in[i].source == PinValue::Source::Live && !tool_signal.empty() && in[i].signal == tool_signal;
    if (on_tool[0] == on_tool[1])
      throw LoadError(
          pivot.net->where(),
          kPin + " follows " + s + ".out, but " +
              (on_tool[0] ? "both " + s + ".in0 and " + s + ".in1 are on " + tool_signal +
                                ": the pivot length would grow by twice the tool offset"
                          : "neither " + s + ".in0 nor " + s + ".in1 is on the signal " + kToolOffset + " drives (" +
                                (tool_signal.empty() ? "it is netted nowhere" : tool_signal) + ")") +
              "; " + kWhy);
    const int t = on_tool[0] ? 0 : 1, c = 1 - t;
    const std::string tool_in = s + ".in" + std::to_string(t), constant_in = s + ".in" + std::to_string(c);

    const Value gain_t = constant(s + ".gain" + std::to_string(t), 1.0);
    if (gain_t.value != 1.0)
      throw LoadError(gain_t.where, s + ".gain" + std::to_string(t) + " = " + format_number(gain_t.value) + ": " +
                                        tool_in + " (the tool offset) must enter the pivot length with gain 1; " +
                                        kWhy);
    const Value value_c = constant_input(in[c], constant_in);
    const Value gain_c = constant(s + ".gain" + std::to_string(c), 1.0);
    const Value offset = constant(s + ".offset", 0.0);
    p.mechanical_mm = gain_c.value * value_c.value + offset.value;

    const std::string nets = at(*pivot.net) + (out_net == pivot.net ? "" : ", " + at(*out_net));
    p.from = {"Pm = " + format_number(p.mechanical_mm) + ", the mechanical pivot length: " + kPin + " follows " + s +
                  ".out (" + nets + "), a sum2 (" + at(*sum->loaded) + "):",
              "out = in0 * gain0 + in1 * gain1 + offset = the G43 offset + Pm, Pm = in" + std::to_string(c) +
                  " * gain" + std::to_string(c) + " + offset, with",
              "  in" + std::to_string(t) + ": " + kToolOffset + ", the G43 offset (" + at(*in[t].net) + "), gain" +
                  std::to_string(t) + " = 1: " + gain_t.from,
              "  in" + std::to_string(c) + " = " + format_number(value_c.value) + ": " + value_c.from,
              "  gain" + std::to_string(c) + " = " + format_number(gain_c.value) + ": " + gain_c.from,
              "  offset = " + format_number(offset.value) + ": " + offset.from};
    return p;
  }

 private:
  struct Value {
    double value = 0.0;
    std::string from;
    SourceLocation where;  // the line that set it, or the KINEMATICS line
  };

  std::string at(const HalCommand& c) const { return cite(c.path, c.line, c.text, ini_.folder()); }

  // A sum2 pin or parameter that must hold a constant (pin_value's rules; not set: sum2's default).
  Value constant(const std::string& name, double default_value) const {
    const PinValue v = pin_value(hal_, name, default_value);
    if (v.source == PinValue::Source::Live)
      throw LoadError(v.net->where(), name + " follows " + v.driver + " at run time (both are on signal " + v.signal +
                                          ", which no sets gives a value); volkins takes the geometry from the machine "
                                          "file: set it with setp");
    Value value{v.value, "", k_.entry->where()};
    if (v.source == PinValue::Source::Default) {
      value.from = "not set in the HAL files read (sum2's default)";
      return value;
    }
    value.from = at(*v.command);
    if (v.source == PinValue::Source::Sets) value.from += " (its signal, " + at(*v.net) + ")";
    value.where = v.command->where();
    return value;
  }

  // The input that is not the tool offset: a constant, or 5axisgui's pivot_len.
  Value constant_input(const PinValue& in, const std::string& name) const {
    if (in.source != PinValue::Source::Live) return constant(name, 0.0);
    std::string gui_signal;
    if (!net_of_pin(hal_, kGuiPin, &gui_signal) || gui_signal != in.signal)
      throw LoadError(in.net->where(), name + " follows " + in.driver + " at run time (both are on signal " +
                                           in.signal +
                                           ", which no sets gives a value): the pivot length's other part must be a "
                                           "constant; volkins takes the geometry from the machine file: set it with "
                                           "setp (or take it from " +
                                           kGuiPin + ", as the bridgemill sample does)");
    const HalCommand* gui = nullptr;
    std::vector<std::string> arguments;
    for (const HalCommand& c : hal_.commands)
      if (const auto load = loadusr_of(c);
          load && !gui && std::filesystem::path(load->module).filename() == "5axisgui") {
        gui = &c;
        arguments = load->arguments;
      }
    if (!gui)
      throw LoadError(in.net->where(), name + " follows " + kGuiPin +
                                           ", but no `loadusr 5axisgui` is in the HAL "
                                           "files read: init takes the pivot length from its pivot_len= argument");
    // 5axisgui runs each argument as Python (`pivot_len=300`): the last one wins.
    Value v{kGuiDefault, "", gui->where()};
    bool given = false;
    for (const std::string& a : arguments)
      if (a.rfind("pivot_len=", 0) == 0) {
        if (!parse_number(a.substr(10), v.value))
          throw LoadError(gui->where(), "`" + a +
                                            "`: 5axisgui's pivot_len is not a number (init takes the pivot "
                                            "length from it)");
        given = true;
      }
    v.from = kGuiPin + " (" + at(*in.net) + "), 5axisgui's pivot_len: " + at(*gui) +
             (given ? "" : ", no pivot_len=: 5axisgui's default 250 (\"to agree with default in 5axiskins.c\")");
    return v;
  }

  const LinuxcncIni& ini_;
  const HalConfig& hal_;
  const KinematicsLine& k_;
  const std::vector<Instance> instances_ = sum2_instances(hal_);
};

}  // namespace

PivotLength pivot_length(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& kinematics) {
  return Resolver(ini, hal, kinematics).run();
}

}  // namespace vc::init
