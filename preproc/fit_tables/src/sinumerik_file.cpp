#include "vc/fit_tables/sinumerik_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "vc/tables/number_text.hpp"

namespace vc::fit_tables {
namespace {

constexpr double kExactResolution = 1e-9;  // "0": values written to 1e-9 mm or deg

// The number of decimals that shows a multiple of `resolution` exactly (0.0001 -> 4).
int decimals_of(double resolution) {
  if (!(resolution > 0)) resolution = kExactResolution;
  for (int d = 0; d < 9; ++d) {
    const double scaled = resolution * std::pow(10.0, d);
    if (std::abs(scaled - std::round(scaled)) < 1e-6 * scaled) return d;
  }
  return 9;
}

// Fixed decimals without trailing zeros, at least one decimal as the manual writes them
// ("0.003", "1.0", "-200.0"); never "-0.0".
std::string decimal_text(double v, int decimals) {
  return without_negative_zero(without_trailing_zeros(fixed_text(v, decimals), 1));
}

std::string value_text(double v, double resolution) {
  const double step = resolution > 0 ? resolution : kExactResolution;
  return decimal_text(std::round(v / step) * step, decimals_of(step));
}

std::string position_text(double v) { return decimal_text(v, 9); }

bool rotary(const machine::Model& model, int joint) {
  return model.axes[static_cast<std::size_t>(joint)].type == machine::AxisType::Rotary;
}

std::string ax(int joint) { return "AX" + std::to_string(joint + 1); }

// One written table: its node positions and values in the control's units (mm or deg).
struct Written {
  int input = 0, output = 0;
  double min = 0.0, max = 0.0;
  bool modulo = false;
  std::vector<double> values;
  std::string what;  // a comment: "X positioning", "Y->X squareness", ...
};

Written written(const machine::Model& model, const TableSet& set, const Table& t, const Eigen::VectorXd& x,
                SinumerikResolution res) {
  Written w;
  w.input = t.input;
  w.output = t.output;
  w.what = set.name(model, t) + " (" + kind_name(t.kind) + ")";
  const double resolution = rotary(model, t.output) ? res.deg : res.mm;
  auto to_resolution = [&](double v) {
    const double step = resolution > 0 ? resolution : kExactResolution;
    return std::round(v / step) * step;
  };
  if (t.kind == TableKind::Squareness) {
    // 2 nodes over the input's travel: linear interpolation between s x MIN and s x MAX is s x input.
    const machine::Axis& in = model.axes[static_cast<std::size_t>(t.input)];
    const double s = x[t.first_unknown];
    w.min = in.travel_min;
    w.max = in.travel_max;
    w.values = {to_resolution(s * w.min), to_resolution(s * w.max)};
    return w;
  }
  w.min = t.nodes.front();
  w.max = t.nodes.back();
  w.modulo = t.modulo;
  // LEC holds the measuring system's error: a positive value moves the axis negative (K3 4.4.2.1).
  const double sign = t.kind == TableKind::Positioning ? -1.0 : 1.0;
  for (std::size_t k = 0; k < t.nodes.size(); ++k)
    w.values.push_back(to_resolution(sign * x[t.unknown_of_node(static_cast<int>(k))]));
  return w;
}

std::string file_comment(const machine::Model& model, const std::string& what) {
  std::string s = "; volcomp fit-tables: " + what + " for " + model.info.name + " (" + model.path + ")\n";
  s += "; machine axes:";
  for (std::size_t j = 0; j < model.axes.size(); ++j)
    s += " " + ax(static_cast<int>(j)) + "=" + model.axes[j].letter +
         (rotary(model, static_cast<int>(j)) ? "(deg)" : "(mm)");
  return s + "\n";
}

}  // namespace

SinumerikResolution sinumerik_resolution(const Controller& controller) {
  SinumerikResolution r;
  for (const TableSpec& t : controller.tables) {
    if (t.resolution_um > 0) r.mm = r.mm > 0 ? std::min(r.mm, t.resolution_um * 1e-3) : t.resolution_um * 1e-3;
    if (t.resolution_deg > 0) r.deg = r.deg > 0 ? std::min(r.deg, t.resolution_deg) : t.resolution_deg;
  }
  return r;
}

std::vector<SinumerikFile> sinumerik_files(const machine::Model& model, const TableSet& set, const Eigen::VectorXd& x,
                                           SinumerikResolution res) {
  std::vector<Written> lec, cec;
  for (const Table& t : set.tables) {
    if (t.direction_dependent)
      throw std::invalid_argument("the Sinumerik files here hold tables for both directions only; " +
                                  set.name(model, t) + " is direction dependent");
    (t.kind == TableKind::Positioning ? lec : cec).push_back(written(model, set, t, x, res));
  }
  std::vector<SinumerikFile> files;
  if (!lec.empty()) {
    std::string s = "%_N_AX_EEC_INI\nCHANDATA(1)\n" +
                    file_comment(model, "leadscrew / measuring system error compensation (LEC)") +
                    "; values: the measuring system's error in mm (deg for a rotary axis), the fit's correction "
                    "negated\n";
    for (const Written& w : lec) {
      const std::string axis = ax(w.input);
      s += "; " + w.what + "\n";
      for (std::size_t n = 0; n < w.values.size(); ++n)
        s += "$AA_ENC_COMP[0," + std::to_string(n) + "," + axis +
             "]=" + value_text(w.values[n], rotary(model, w.output) ? res.deg : res.mm) + "\n";
      s += "$AA_ENC_COMP_STEP[0," + axis + "]=" + position_text((w.max - w.min) / (w.values.size() - 1)) + "\n";
      s += "$AA_ENC_COMP_MIN[0," + axis + "]=" + position_text(w.min) + "\n";
      s += "$AA_ENC_COMP_MAX[0," + axis + "]=" + position_text(w.max) + "\n";
      s += "$AA_ENC_COMP_IS_MODULO[0," + axis + "]=" + (w.modulo ? "1" : "0") + "\n";
    }
    files.push_back({"AX_EEC.INI", s + "M17\n"});
  }
  if (!cec.empty()) {
    std::string s = "%_N_NC_CEC_INI\nCHANDATA(1)\n" +
                    file_comment(model, "sag / angularity compensation (CEC): straightness and squareness") +
                    "; values: the correction added to the output axis, mm (deg for a rotary output)\n";
    for (std::size_t t = 0; t < cec.size(); ++t) {
      const Written& w = cec[t];
      const std::string i = "[" + std::to_string(t) + "]";
      s += "; table " + std::to_string(t) + ": " + w.what + "\n";
      for (std::size_t n = 0; n < w.values.size(); ++n)
        s += "$AN_CEC[" + std::to_string(t) + "," + std::to_string(n) +
             "]=" + value_text(w.values[n], rotary(model, w.output) ? res.deg : res.mm) + "\n";
      s += "$AN_CEC_INPUT_AXIS" + i + "=(" + ax(w.input) + ")\n";
      s += "$AN_CEC_OUTPUT_AXIS" + i + "=(" + ax(w.output) + ")\n";
      s += "$AN_CEC_STEP" + i + "=" + position_text((w.max - w.min) / (w.values.size() - 1)) + "\n";
      s += "$AN_CEC_MIN" + i + "=" + position_text(w.min) + "\n";
      s += "$AN_CEC_MAX" + i + "=" + position_text(w.max) + "\n";
      s += "$AN_CEC_DIRECTION" + i + "=0\n";
      s += "$AN_CEC_MULT_BY_TABLE" + i + "=0\n";
      s += "$AN_CEC_IS_MODULO" + i + "=" + (w.modulo ? "1" : "0") + "\n";
    }
    files.push_back({"NC_CEC.INI", s + "M17\n"});
  }
  return files;
}

std::string sinumerik_setup_lines(const TableSet& set, const std::vector<SinumerikFile>& files) {
  int lec_points = 0, cec_points = 0, cec_tables = 0;
  for (const Table& t : set.tables) {
    const int n = t.kind == TableKind::Squareness ? 2 : static_cast<int>(t.nodes.size());
    if (t.kind == TableKind::Positioning) {
      lec_points = std::max(lec_points, n);
    } else {
      cec_points = std::max(cec_points, n);
      ++cec_tables;
    }
  }
  std::string names;
  for (const SinumerikFile& f : files) names += (names.empty() ? "" : " and ") + f.file_name;
  std::string s = "; volcomp fit-tables: loading " + names +
                  " into a SINUMERIK 840D sl (Function Manual Extended Functions, K3 Compensations, sec. 4.4)\n";
  if (lec_points > 0)
    s += "; - MD38000 $MA_MM_ENC_COMP_MAX_POINTS >= " + std::to_string(lec_points) +
         " for every axis with a table (takes effect after power-up, which reformats the static user memory)\n";
  if (cec_points > 0)
    s += "; - MD18342 $MN_MM_CEC_MAX_POINTS[t] >= " + std::to_string(cec_points) + " for the " +
         std::to_string(cec_tables) + " CEC tables t = 0 .. " + std::to_string(cec_tables - 1) +
         " (an 828D has 8 tables of 200 points)\n";
  s += "; - load the files while MD32700 $MA_ENC_COMP_ENABLE and MD32710 $MA_CEC_ENABLE are 0 (tables load only "
       "while their function is off)\n"
       "; - then MD32700 $MA_ENC_COMP_ENABLE[0] = 1 for every axis with an EEC table, MD32710 $MA_CEC_ENABLE = 1 for "
       "every CEC output axis, SD41300 $SN_CEC_TABLE_ENABLE[t] = 1 for every CEC table; LEC acts once the axis is "
       "referenced\n"
       "; - axes: AXn is the machine file's n-th axis, which must be machine axis n (MD10000)\n"
       "; - the sign of a CEC value is not stated in the documents read: written as the correction added to the output "
       "axis; check one table on the machine (a +0.01 mm value moves its output axis +0.01 mm in the service display "
       "'Compensation, sag + temperature') before use, and negate the $AN_CEC values if it moves the other way\n";
  return s;
}

// ---------------------------------------------------------------------------------------------
// The reader.
namespace {

struct Field {
  double value = 0.0;
  SourceLocation where;
};

struct PendingTable {
  SinumerikTable::Kind kind;
  int index = 0;
  SourceLocation first;
  std::optional<Field> step, min, max, modulo, input, output;
  std::map<int, Field> values;
};

class SinumerikReader {
 public:
  SinumerikReader(const std::string& text, std::string path) : text_(text), path_(std::move(path)) {}

  std::vector<SinumerikTable> read() {
    std::istringstream in(text_);
    int line_no = 0;
    enum { Header, Chandata, Body, Ended } state = Header;
    for (std::string raw; std::getline(in, raw);) {
      ++line_no;
      if (!raw.empty() && raw.back() == '\r') raw.pop_back();
      std::string line = raw.substr(0, raw.find(';'));  // a comment runs to the end of the line
      std::size_t first = line.find_first_not_of(" \t");
      if (first == std::string::npos) continue;
      std::size_t last = line.find_last_not_of(" \t");
      const std::string code = line.substr(first, last - first + 1);
      const int col = static_cast<int>(first) + 1;
      switch (state) {
        case Header:
          if (code == "%_N_AX_EEC_INI") {
            kind_ = SinumerikTable::Kind::Lec;
          } else if (code == "%_N_NC_CEC_INI") {
            kind_ = SinumerikTable::Kind::Cec;
          } else {
            fail(line_no, col, "expected the header %_N_AX_EEC_INI or %_N_NC_CEC_INI, not '" + code + "'");
          }
          state = Chandata;
          break;
        case Chandata:
          if (code != "CHANDATA(1)") fail(line_no, col, "expected CHANDATA(1) after the header, not '" + code + "'");
          state = Body;
          break;
        case Body:
          if (code == "M17") {
            state = Ended;
          } else {
            assignment(code, line_no, col);
          }
          break;
        case Ended:
          fail(line_no, col, "'" + code + "' after M17 (the end of the file)");
      }
    }
    if (state == Header) fail(1, 1, "empty file: expected the header %_N_AX_EEC_INI or %_N_NC_CEC_INI");
    if (state != Ended) fail(line_no + 1, 1, "the file ends without M17");
    std::vector<SinumerikTable> out;
    for (auto& entry : tables_) out.push_back(finish(entry.second));
    return out;
  }

 private:
  [[noreturn]] void fail(int line, int column, const std::string& message) const {
    throw LoadError({path_, line, column}, message);
  }
  [[noreturn]] void fail(const SourceLocation& at, const std::string& message) const { throw LoadError(at, message); }

  static bool whole(const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
  }

  int integer(const std::string& s, int line, int col, const std::string& what) const {
    if (!whole(s) || s.size() > 6) fail(line, col, what + " must be a whole number >= 0, not '" + s + "'");
    return std::stoi(s);
  }

  double number(const std::string& s, int line, int col) const {
    double v = 0.0;
    const char* end = s.data() + s.size();
    const auto [ptr, ec] = std::from_chars(s.data(), end, v);
    if (s.empty() || ec != std::errc() || ptr != end || !std::isfinite(v))
      fail(line, col, "'" + s + "' is not a number");
    return v;
  }

  // "AX3" -> 2
  int axis(const std::string& s, int line, int col) const {
    if (s.size() < 3 || s.compare(0, 2, "AX") != 0 || !whole(s.substr(2)) || s.substr(2) == "0" || s.size() > 4)
      fail(line, col, "expected a machine axis AX1, AX2, ..., not '" + s + "'");
    return std::stoi(s.substr(2)) - 1;
  }

  // $NAME[a,b,...]=VALUE
  void assignment(const std::string& code, int line, int col) {
    if (code[0] != '$') fail(line, col, "expected a system variable assignment ($...=...), not '" + code + "'");
    const std::size_t open = code.find('['), close = code.find(']'), equals = code.find('=');
    if (open == std::string::npos || close == std::string::npos || equals == std::string::npos || close < open ||
        equals != close + 1)
      fail(line, col, "expected $NAME[INDEX]=VALUE, not '" + code + "'");
    const std::string name = code.substr(1, open - 1);
    std::vector<std::pair<std::string, int>> args;  // text, column
    std::size_t from = open + 1;
    for (;;) {
      const std::size_t comma = code.find(',', from);
      const std::size_t stop = comma == std::string::npos || comma > close ? close : comma;
      args.emplace_back(code.substr(from, stop - from), col + static_cast<int>(from));
      if (stop == close) break;
      from = stop + 1;
    }
    const std::string value = code.substr(equals + 1);
    const int value_col = col + static_cast<int>(equals) + 1;
    const int name_col = col + 1;
    if (kind_ == SinumerikTable::Kind::Lec) {
      lec(name, args, value, line, col, name_col, value_col);
    } else {
      cec(name, args, value, line, col, name_col, value_col);
    }
  }

  PendingTable& table(int key, int line, int col) {
    auto it = tables_.find(key);
    if (it == tables_.end()) {
      PendingTable t;
      t.kind = kind_;
      t.index = key;
      t.first = {path_, line, col};
      it = tables_.emplace(key, t).first;
    }
    return it->second;
  }

  void set(std::optional<Field>& field, double v, const std::string& name, int line, int col) {
    if (field) fail(line, col, name + " is set twice (first at " + field->where.to_string() + ")");
    field = Field{v, {path_, line, col}};
  }

  // The entries LEC and CEC tables share, by the variable's name after its prefix: "" a node's
  // value (its index N the second one), _STEP, _MIN, _MAX, _IS_MODULO. False for any other.
  bool set_shared(PendingTable& t, const std::string& name, const std::string& suffix,
                  const std::vector<std::pair<std::string, int>>& args, double v, int line, int value_col) {
    if (suffix.empty()) {
      const int n = integer(args[1].first, line, args[1].second, "the node N");
      if (t.values.count(n))
        fail(line, args[1].second,
             "node " + std::to_string(n) + " is set twice (first at " + t.values.at(n).where.to_string() + ")");
      t.values[n] = Field{v, {path_, line, args[1].second}};
      return true;
    }
    std::optional<Field>* field = suffix == "_STEP"        ? &t.step
                                  : suffix == "_MIN"       ? &t.min
                                  : suffix == "_MAX"       ? &t.max
                                  : suffix == "_IS_MODULO" ? &t.modulo
                                                           : nullptr;
    if (!field) return false;
    set(*field, v, "$" + name, line, value_col);
    return true;
  }

  void lec(const std::string& name, const std::vector<std::pair<std::string, int>>& args, const std::string& value,
           int line, int col, int name_col, int value_col) {
    const bool values = name == "AA_ENC_COMP";
    const std::vector<std::string> known{"AA_ENC_COMP", "AA_ENC_COMP_STEP", "AA_ENC_COMP_MIN", "AA_ENC_COMP_MAX",
                                         "AA_ENC_COMP_IS_MODULO"};
    if (std::find(known.begin(), known.end(), name) == known.end())
      fail(line, name_col,
           "unknown variable $" + name + " in an EEC file (expected $AA_ENC_COMP, _STEP, _MIN, _MAX, _IS_MODULO)");
    const std::size_t want = values ? 3 : 2;
    if (args.size() != want)
      fail(line, name_col,
           "$" + name + " takes " + std::to_string(want) + " indices (" + (values ? "[e,N,AXi]" : "[e,AXi]") +
               "), not " + std::to_string(args.size()));
    if (integer(args[0].first, line, args[0].second, "the measuring system e") != 0)
      fail(line, args[0].second, "only measuring system 1 (e = 0) is read here");
    const auto& axis_arg = args.back();
    const int a = axis(axis_arg.first, line, axis_arg.second);
    PendingTable& t = table(a, line, col);
    set_shared(t, name, name.substr(std::string("AA_ENC_COMP").size()), args, number(value, line, value_col), line,
               value_col);  // every LEC variable is a shared one (checked above)
  }

  void cec(const std::string& name, const std::vector<std::pair<std::string, int>>& args, const std::string& value,
           int line, int col, int name_col, int value_col) {
    const std::vector<std::string> known{"AN_CEC",           "AN_CEC_INPUT_AXIS",    "AN_CEC_OUTPUT_AXIS",
                                         "AN_CEC_STEP",      "AN_CEC_MIN",           "AN_CEC_MAX",
                                         "AN_CEC_DIRECTION", "AN_CEC_MULT_BY_TABLE", "AN_CEC_IS_MODULO"};
    if (std::find(known.begin(), known.end(), name) == known.end())
      fail(line, name_col,
           "unknown variable $" + name +
               " in a CEC file (expected $AN_CEC, _INPUT_AXIS, _OUTPUT_AXIS, "
               "_STEP, _MIN, _MAX, _DIRECTION, _MULT_BY_TABLE, _IS_MODULO)");
    const bool values = name == "AN_CEC";
    const std::size_t want = values ? 2 : 1;
    if (args.size() != want)
      fail(line, name_col,
           "$" + name + " takes " + std::to_string(want) + " ind" + (values ? "ices ([t,N])" : "ex ([t])") + ", not " +
               std::to_string(args.size()));
    const int index = integer(args[0].first, line, args[0].second, "the table index t");
    PendingTable& t = table(index, line, col);
    if (name == "AN_CEC_INPUT_AXIS" || name == "AN_CEC_OUTPUT_AXIS") {
      if (value.size() < 3 || value.front() != '(' || value.back() != ')')
        fail(line, value_col, "expected a machine axis in parentheses, e.g. (AX1), not '" + value + "'");
      const int a = axis(value.substr(1, value.size() - 2), line, value_col + 1);
      set(name == "AN_CEC_INPUT_AXIS" ? t.input : t.output, a, "$" + name, line, value_col);
      return;
    }
    const double v = number(value, line, value_col);
    if (set_shared(t, name, name.substr(std::string("AN_CEC").size()), args, v, line, value_col)) return;
    if (v != 0.0) {  // DIRECTION, MULT_BY_TABLE
      fail(line, value_col,
           "$" + name +
               " other than 0 is not read here (the writer writes 0: both directions, "
               "no table multiplication)");
    }
  }

  SinumerikTable finish(const PendingTable& p) const {
    const std::string what = p.kind == SinumerikTable::Kind::Lec ? "the EEC table of AX" + std::to_string(p.index + 1)
                                                                 : "CEC table " + std::to_string(p.index);
    const std::string prefix = p.kind == SinumerikTable::Kind::Lec ? "$AA_ENC_COMP" : "$AN_CEC";
    for (const auto& [field, suffix] :
         {std::pair{&p.step, "_STEP"}, {&p.min, "_MIN"}, {&p.max, "_MAX"}, {&p.modulo, "_IS_MODULO"}})
      if (!*field) fail(p.first, what + " has no " + prefix + suffix);
    if (p.kind == SinumerikTable::Kind::Cec) {
      if (!p.input) fail(p.first, what + " has no $AN_CEC_INPUT_AXIS");
      if (!p.output) fail(p.first, what + " has no $AN_CEC_OUTPUT_AXIS");
    }
    SinumerikTable t;
    t.kind = p.kind;
    t.index = p.index;
    t.where = p.first;
    t.input_axis = p.kind == SinumerikTable::Kind::Lec ? p.index : static_cast<int>(p.input->value);
    t.output_axis = p.kind == SinumerikTable::Kind::Lec ? p.index : static_cast<int>(p.output->value);
    t.min = p.min->value;
    t.max = p.max->value;
    t.step = p.step->value;
    if (p.modulo->value != 0.0 && p.modulo->value != 1.0) fail(p.modulo->where, prefix + "_IS_MODULO must be 0 or 1");
    t.modulo = p.modulo->value == 1.0;
    if (!(t.max > t.min)) fail(p.max->where, prefix + "_MAX must be above " + prefix + "_MIN");
    if (!(t.step > 0)) fail(p.step->where, prefix + "_STEP must be above 0");
    // N = (MAX - MIN) / STEP + 1 nodes, a whole number (STEP written to 1e-9).
    const double cells = (t.max - t.min) / t.step;
    const long nodes = std::lround(cells) + 1;
    if (std::abs(cells - std::round(cells)) > 1e-6 * std::max(1.0, cells) || nodes < 2 || nodes > 100000)
      fail(p.step->where, "(MAX - MIN) / STEP = " + std::to_string(cells) + ": not a whole number of intervals");
    for (const auto& [n, field] : p.values)
      if (n >= nodes)
        fail(field.where, "node " + std::to_string(n) + " is beyond the table's " + std::to_string(nodes) +
                              " nodes ((MAX - MIN) / STEP + 1)");
    for (long n = 0; n < nodes; ++n) {
      if (!p.values.count(static_cast<int>(n)))
        fail(p.first, what + " has no value for node " + std::to_string(n) + " of its " + std::to_string(nodes));
      t.values.push_back(p.values.at(static_cast<int>(n)).value);
    }
    return t;
  }

  const std::string& text_;
  std::string path_;
  SinumerikTable::Kind kind_ = SinumerikTable::Kind::Lec;
  std::map<int, PendingTable> tables_;  // LEC: by axis; CEC: by t
};

}  // namespace

std::vector<SinumerikTable> read_sinumerik_file(const std::string& text, const std::string& path) {
  return SinumerikReader(text, path).read();
}

double sinumerik_table_value(const SinumerikTable& t, double position) {
  const double period = t.max - t.min;
  if (t.modulo) {
    position = t.min + std::fmod(position - t.min, period);
    if (position < t.min) position += period;
  }
  const std::vector<double>& v = t.values;
  if (position <= t.min) return v.front();  // held below MIN
  if (position >= t.max) return v.back();   // held above MAX
  const int cells = static_cast<int>(v.size()) - 1;
  const double h = period / cells;
  const int k = std::min(cells - 1, static_cast<int>(std::floor((position - t.min) / h)));
  const double w = (position - (t.min + k * h)) / h;
  return (1.0 - w) * v[static_cast<std::size_t>(k)] + w * v[static_cast<std::size_t>(k) + 1];
}

machine::Joints sinumerik_commanded(const std::vector<SinumerikTable>& tables, const machine::Joints& q) {
  machine::Joints out = q;
  for (const SinumerikTable& t : tables) {
    if (t.input_axis >= q.size() || t.output_axis >= q.size())
      throw std::invalid_argument(t.where.to_string() + ": AX" +
                                  std::to_string(std::max(t.input_axis, t.output_axis) + 1) +
                                  " is beyond the machine's " + std::to_string(q.size()) + " axes");
    const double v = sinumerik_table_value(t, q[t.input_axis]);
    out[t.output_axis] += t.kind == SinumerikTable::Kind::Lec ? -v : v;
  }
  return out;
}

}  // namespace vc::fit_tables
