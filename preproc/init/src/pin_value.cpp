#include "vc/init/pin_value.hpp"

#include "vc/init/number.hpp"

namespace vc::init {

PinValue pin_value(const HalConfig& hal, const std::string& pin, double default_value) {
  PinValue v;
  v.value = default_value;
  v.net = net_of_pin(hal, pin, &v.signal);
  auto assign = [&](const HalCommand& c, const std::string& value, PinValue::Source source) {
    if (!parse_number(value, v.value))
      throw LoadError(c.where(), "'" + value + "' is not a number (the value of " + pin + ")");
    v.source = source;
    v.command = &c;
  };
  bool signal_set = false;
  std::string driver;
  for (const HalCommand& c : hal.commands) {
    if (const auto setp = setp_of(c); setp && setp->target == pin) assign(c, setp->value, PinValue::Source::Setp);
    if (v.signal.empty()) continue;
    if (const auto sets = sets_of(c); sets && sets->target == v.signal) {
      assign(c, sets->value, PinValue::Source::Sets);
      signal_set = true;
    }
    if (const auto net = net_of(c); net && net->signal == v.signal)
      for (const NetPin& p : net->pins)
        if (p.name != pin && !p.reader && driver.empty()) driver = p.name;
  }
  if (!signal_set && !driver.empty()) {
    v.source = PinValue::Source::Live;
    v.command = nullptr;
    v.driver = driver;
  }
  return v;
}

}  // namespace vc::init
