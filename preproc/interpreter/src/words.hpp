// What the interpreter's files share: a block's evaluated words, LinuxCNC's parameter
// numbers, units. Private to preproc/interpreter/src.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include "vc/interpreter/interpreter.hpp"

namespace vc::interpreter {

inline constexpr double kInch = 25.4;

// Parameter numbers of a LinuxCNC .var file.
inline constexpr int kG28Home = 5161, kG30Home = 5181;
inline constexpr int kCoordinateSystem = 5220;         // active system 1..9
inline constexpr int kG92Applied = 5210, kG92 = 5211;  // G92 offsets on (1) and their values X..C
inline int offset_parameter(int system, int axis) { return 5201 + 20 * system + axis; }  // 5221 = G54 X
inline int rotation_parameter(int system) { return 5210 + 20 * system; }                 // 5230 = G54 R

// "G59.1" for 591 (G codes are kept x10).
inline std::string g_name(int code) {
  const int whole = code / 10, tenth = code % 10;
  return "G" + std::to_string(whole) + (tenth ? "." + std::to_string(tenth) : "");
}

// The words of a block with their values (evaluated with the parameters from before the
// line), sorted into letters and G/M codes.
struct Interpreter::Words {
  struct Value {
    bool has = false;
    double value = 0.0;
    int index = -1;  // into block.words
    int offset = 0;
  };
  struct Code {
    int code;  // x10: G59.1 = 591
    int index;
    int offset;
  };
  std::array<Value, 28> letters{};  // A..Z, then '@' and '^' (polar distance and angle)
  static std::size_t slot(char c) { return c == '@' ? 26 : c == '^' ? 27 : static_cast<std::size_t>(c - 'A'); }
  std::vector<Code> g, m;

  const Value& operator[](char c) const { return letters[slot(c)]; }
  bool polar() const { return has('@') || has('^'); }
  // A word that must hold a whole number (tool, turns, L, P): its value, or -1 if it does not.
  int whole(char c) const {
    const double v = get(c);
    return v == std::floor(v) && v >= 0 && v <= 1e6 ? static_cast<int>(v) : -1;
  }
  bool has(char c) const { return (*this)[c].has; }
  // Where the first axis or arc word is written (for messages about the motion).
  int first_motion_offset() const {
    int first = -1;
    for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'I', 'J', 'K', 'R', '@', '^'})
      if (has(c) && (first < 0 || (*this)[c].offset < first)) first = (*this)[c].offset;
    return std::max(first, 0);
  }
  double get(char c) const { return (*this)[c].value; }
  const Code* find_g(std::initializer_list<int> codes) const {
    for (const Code& c : g)
      if (std::find(codes.begin(), codes.end(), c.code) != codes.end()) return &c;
    return nullptr;
  }
  // The line's motion code (group 1), if any: G80 only if there is no other.
  const Code* motion_code() const {
    const Code* c = find_g({G_0,  G_1,  G_2,    G_3,    G_5,  G_5_1,  G_5_2, G_73, G_74,
                            G_81, G_82, G_83,   G_84,   G_85, G_86,   G_88,  G_89,  // (G5.3: splines.cpp)
                            G_70, G_71, G_71_1, G_71_2, G_72, G_72_1, G_72_2});
    return c ? c : find_g({G_80});
  }
  const Code* find_m(std::initializer_list<int> codes) const {
    for (const Code& c : m)
      if (std::find(codes.begin(), codes.end(), c.code) != codes.end()) return &c;
    return nullptr;
  }
};

// The signed angle (rad) an arc sweeps from angle t0 to angle t1 about its center, in
// `turns` (P) turns, as LinuxCNC's arcs do: (0, 2 pi] counterclockwise, [-2 pi, 0) clockwise
// (a full turn if t1 is t0), plus the further turns (arcs.cpp).
double arc_sweep(double t0, double t1, bool clockwise, int turns);

}  // namespace vc::interpreter
