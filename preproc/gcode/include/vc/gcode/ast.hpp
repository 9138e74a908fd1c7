// The syntax tree of one RS274/NGC block (LinuxCNC's dialect): words whose values are
// numbers or expressions, parameter assignments, comments. Plain structs; the grammar
// (parser_def.hpp) builds them and evaluate.hpp gives expressions their values. The meaning
// of the words (modal groups, units, arcs) is the interpreter's business, not the AST's.
#pragma once

#include <boost/spirit/home/x3/support/ast/variant.hpp>
#include <string>
#include <vector>

namespace vc::gcode::ast {
namespace x3 = boost::spirit::x3;

struct NumberedParameter;  // #n, #[expr]
struct NamedParameter {    // #<name>, #<_global>: name lower case, without spaces
  std::string name;
};
struct Unary;  // ABS[e], -e, ...
struct Atan2;  // ATAN[y]/[x]
struct Chain;  // e op e op e ... (one precedence level, left to right)

struct Expression : x3::variant<double, NamedParameter, x3::forward_ast<NumberedParameter>, x3::forward_ast<Unary>,
                                x3::forward_ast<Atan2>, x3::forward_ast<Chain>> {
  using base_type::base_type;
  using base_type::operator=;
};

enum class Function { Minus, Plus, Abs, Acos, Asin, Cos, Exp, Fix, Fup, Round, Ln, Sin, Sqrt, Tan, Exists };
// By precedence, highest first: **; * / MOD; + -; EQ NE GT GE LT LE; AND OR XOR.
enum class Operator { Power, Times, Divide, Modulo, Plus, Minus, Eq, Ne, Gt, Ge, Lt, Le, And, Or, Xor };

struct NumberedParameter {
  Expression index;
};
struct Unary {
  Function function;
  Expression operand;
};
struct Atan2 {
  Expression y, x;
};
struct Operation {
  Operator op;
  Expression operand;
};
struct Chain {
  Expression first;
  std::vector<Operation> rest;  // all of one precedence level
};

}  // namespace vc::gcode::ast
