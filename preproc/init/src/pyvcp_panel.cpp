#include "vc/init/pyvcp_panel.hpp"

#include <algorithm>
#include <cmath>

#include "vc/init/number.hpp"

namespace vc::init {
namespace {

// The panel's text with its <!-- comments --> blanked (line ends kept, so offsets keep their lines).
std::string without_comments(std::string text) {
  for (std::size_t start = text.find("<!--"); start != std::string::npos; start = text.find("<!--", start)) {
    const std::size_t end = text.find("-->", start + 4);
    const std::size_t stop = end == std::string::npos ? text.size() : end + 3;
    for (std::size_t i = start; i < stop; ++i)
      if (text[i] != '\n') text[i] = ' ';
    start = stop;
  }
  return text;
}

struct Element {
  std::string text;  // trimmed
  std::size_t offset = 0;
};

// <tag>text</tag> inside [begin, end) of `xml`.
bool element(const std::string& xml, std::size_t begin, std::size_t end, const std::string& tag, Element& e) {
  const std::string open = "<" + tag + ">", close = "</" + tag + ">";
  const std::size_t at = xml.find(open, begin);
  if (at == std::string::npos || at >= end) return false;
  const std::size_t stop = xml.find(close, at);
  if (stop == std::string::npos || stop > end) return false;
  e.offset = at;
  e.text = trim(std::string_view(xml).substr(at + open.size(), stop - at - open.size()));
  return true;
}

}  // namespace

std::vector<PyvcpSlider> pyvcp_sliders(const LinuxcncIni& ini) {
  std::vector<PyvcpSlider> sliders;
  const IniEntry* entry = ini.find("DISPLAY", "PYVCP");
  if (!entry || entry->value.empty()) return sliders;
  const std::string path =
      absolute_path(entry->value.front() == '/' ? entry->value : ini.folder() + "/" + entry->value);
  const TextFile file = read_text_file(path, "pyvcp panel ([DISPLAY]PYVCP, " + ini.cite(*entry) + ")");
  std::string raw;
  std::vector<std::size_t> line_start;
  for (const TextLine& l : file.lines) {
    line_start.push_back(raw.size());
    raw += l.text + "\n";
  }
  const std::string xml = without_comments(raw);
  auto line_of = [&](std::size_t offset) {
    return static_cast<int>(std::upper_bound(line_start.begin(), line_start.end(), offset) - line_start.begin());
  };
  auto quote = [&](const Element& e) {
    const int line = line_of(e.offset);
    return cite(path, line, trim(file.line(line).text), ini.folder());
  };
  auto number = [&](const Element& e, const std::string& what) {
    double v = 0.0;
    if (!parse_number(e.text, v))
      throw LoadError({path, line_of(e.offset)},
                      "'" + e.text + "' is not a number (the " + what + " of a pyvcp slider)");
    return v;
  };
  for (std::size_t at = xml.find("<scale>"); at != std::string::npos; at = xml.find("<scale>", at + 1)) {
    std::size_t end = xml.find("</scale>", at);
    if (end == std::string::npos) end = xml.size();
    Element halpin, initval, low, high, resolution, param;
    if (!element(xml, at, end, "halpin", halpin)) continue;  // pyvcp names it scale.N: no geometry signal's
    const std::string& h = halpin.text;
    if (h.size() < 2 || (h.front() != '"' && h.front() != '\'') || h.back() != h.front()) continue;
    PyvcpSlider s;
    s.halpin = h.substr(1, h.size() - 2);
    s.where = {path, line_of(at)};
    if (element(xml, at, end, "param_pin", param) && param.text != "0")
      throw LoadError(s.where, "the pyvcp slider " + s.halpin +
                                   " has a <param_pin>: its value is set from outside the panel at run time, "
                                   "which init cannot read");
    double min = 0.0, max = 10.0;  // pyvcp_scale's min_ and max_
    std::string min_from = "pyvcp's default min_ 0", max_from = "pyvcp's default max_ 10";
    if (element(xml, at, end, "min_", low)) min = number(low, "min_"), min_from = quote(low);
    if (element(xml, at, end, "max_", high)) max = number(high, "max_"), max_from = quote(high);
    if (element(xml, at, end, "initval", initval)) {
      s.initial = number(initval, "initval");
      s.from = quote(initval);
    } else {
      s.from = "pyvcp's default initval 0 (the <scale> at " + display_path(path, ini.folder()) + ":" +
               std::to_string(s.where.line) + ")";
    }
    // pyvcp_scale holds its start within min_ .. max_ (min_ first).
    if (s.initial < min) {
      s.initial = min;
      s.from += ", held at " + min_from;
    } else if (s.initial > max) {
      s.initial = max;
      s.from += ", held at " + max_from;
    }
    const double step = element(xml, at, end, "resolution", resolution) ? number(resolution, "resolution") : 1.0;
    if (step > 0 && std::abs(s.initial / step - std::round(s.initial / step)) > 1e-9)
      throw LoadError(s.where, "the pyvcp slider " + s.halpin + " starts at " + format_number(s.initial) +
                                   ", not a multiple of its resolution " + format_number(step) +
                                   " (Tk rounds it): give an initval on the resolution");
    sliders.push_back(s);
  }
  return sliders;
}

const PyvcpSlider* slider_of_pin(const std::vector<PyvcpSlider>& sliders, const std::string& pin) {
  for (const PyvcpSlider& s : sliders)
    if (pin == "pyvcp." + s.halpin + "-f") return &s;
  return nullptr;
}

}  // namespace vc::init
