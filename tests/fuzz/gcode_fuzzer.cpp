// libFuzzer target: any bytes, split into lines, through the reader (parse_block), the
// expression evaluator and the interpreter. Refusals (SyntaxError, LoadError) are the
// expected answers to bad input; a crash, a hang, a sanitizer report or any other
// exception is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vc/gcode/evaluate.hpp"
#include "vc/gcode/parser.hpp"
#include "vc/interpreter/interpreter.hpp"
#include "vc/tables/source_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const vc::interpreter::ToolTable tools{{1, vc::interpreter::mill_tool(1, 100.0, 10.0)},
                                                {2, vc::interpreter::mill_tool(2, 85.5, 6.0)}};
  static const vc::gcode::Parameters var = [] {
    vc::gcode::Parameters p;
    p[5221] = 250;
    p[5222] = 150;
    p[5223] = -340;
    return p;
  }();
  vc::interpreter::Setup setup;
  setup.file = "fuzz.ngc";
  setup.machine_axes = 0b110111;  // X Y Z B C
  setup.tools = &tools;
  setup.var_file = &var;
  vc::interpreter::Interpreter interpreter(setup);
  vc::gcode::Block block;
  vc::interpreter::Effect effect;
  vc::gcode::Parameters parameters;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  int line = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    const std::string_view raw = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    ++line;
    try {
      vc::gcode::parse_block(raw, block);
      for (const auto& w : block.words) {
        try {
          (void)vc::gcode::evaluate(w.value, parameters, w.begin);
        } catch (const vc::gcode::SyntaxError&) {
        }
      }
      try {
        vc::gcode::apply_assignments(block, parameters);
      } catch (const vc::gcode::SyntaxError&) {
      }
      interpreter.execute(block, line, effect);
    } catch (const vc::gcode::SyntaxError& e) {
      if (e.offset < 0 || static_cast<std::size_t>(e.offset) > raw.size()) __builtin_trap();  // offset in the line
    } catch (const vc::LoadError&) {
    }
  }
  return 0;
}
