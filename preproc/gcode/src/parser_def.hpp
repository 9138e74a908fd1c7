// The grammar of RS274/NGC values and expressions, LinuxCNC's dialect, over a line that has
// been lower-cased and stripped of spaces and comments (as LinuxCNC's reader does first).
//
//   value      = number | '[' expression ']' | parameter | function | ('-' | '+') value
//   expression = xor_level: level ((and|or|xor) level)*   (lowest precedence)
//                compare:   sum ((eq|ne|gt|ge|lt|le) sum)*
//                sum:       product (('+'|'-') product)*
//                product:   power (('*'|'/'|mod) power)*
//                power:     value ('**' value)*                (highest)
//   parameter  = '#' ('<' name '>' | value)
//   function   = name '[' expression ']' | atan '[' e ']' '/' '[' e ']' | exists '[' #<name> ']'
// Numbers have no exponent and no inf/nan ("1e5" is the word e). The grammar builds the AST
// only; evaluate.cpp gives it meaning.
#pragma once

#include <boost/spirit/home/x3.hpp>
#include <charconv>
#include <cstdint>

#include "ast_adapted.hpp"

namespace vc::gcode::parser {
namespace x3 = boost::spirit::x3;

// A sign, then digits with an optional point anywhere ("1", "1.", ".5"), and nothing else.
// The value is the correctly rounded double, as LinuxCNC's strtod gives: digits as an integer
// m < 2^53 and at most 22 after the point are m / 10^k in one division of two exact doubles,
// itself correctly rounded (Clinger's fast path: what CAM writes, in a fraction of
// std::from_chars' time); anything longer goes to std::from_chars.
// Returns the end of the number, or `first` if there is none.
inline const char* scan_number(const char* first, const char* last, double& value) {
  static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                            1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr std::uint64_t kExactInteger = std::uint64_t{1} << 53;
  const char* it = first;
  const bool negative = it != last && *it == '-';
  if (it != last && (*it == '-' || *it == '+')) ++it;
  const char* const begin = it;
  std::uint64_t mantissa = 0;  // of all the digits (wraps past 19 of them: then not used)
  const auto digits_from = [&mantissa, last](const char* p) {
    for (; p != last && *p >= '0' && *p <= '9'; ++p) mantissa = 10 * mantissa + static_cast<std::uint64_t>(*p - '0');
    return p;
  };
  it = digits_from(it);
  const long integer_digits = it - begin;
  long fraction_digits = 0;
  if (it != last && *it == '.') {
    const char* const fraction = it + 1;
    it = digits_from(fraction);
    fraction_digits = it - fraction;
  }
  const long digits = integer_digits + fraction_digits;
  if (digits == 0) return first;
  if (digits <= 19 && mantissa <= kExactInteger && fraction_digits <= 22) {
    value = static_cast<double>(mantissa) / kPowersOfTen[fraction_digits];
  } else {
    const auto [end, error] = std::from_chars(begin, it, value);
    if (error != std::errc() || end != it) return first;
  }
  if (negative) value = -value;
  return it;
}

struct NgcNumber : x3::parser<NgcNumber> {
  using attribute_type = double;
  static const bool has_attribute = true;

  template <typename Iterator, typename Context, typename RContext, typename Attribute>
  bool parse(Iterator& first, const Iterator& last, const Context& context, const RContext&,
             Attribute& attribute) const {
    x3::skip_over(first, last, context);
    if (first == last) return false;
    const char* const text = &*first;
    double value = 0.0;
    const char* const end = scan_number(text, text + (last - first), value);
    if (end == text) return false;
    x3::traits::move_to(value, attribute);
    first += end - text;
    return true;
  }
};
const NgcNumber number{};

struct FunctionSymbols : x3::symbols<ast::Function> {
  FunctionSymbols() {
    add("abs", ast::Function::Abs)("acos", ast::Function::Acos)("asin", ast::Function::Asin)("cos", ast::Function::Cos)(
        "exp", ast::Function::Exp)("fix", ast::Function::Fix)("fup", ast::Function::Fup)("round", ast::Function::Round)(
        "ln", ast::Function::Ln)("sin", ast::Function::Sin)("sqrt", ast::Function::Sqrt)("tan", ast::Function::Tan);
  }
};
struct SignSymbols : x3::symbols<ast::Function> {
  SignSymbols() { add("-", ast::Function::Minus)("+", ast::Function::Plus); }
};
struct LogicSymbols : x3::symbols<ast::Operator> {
  LogicSymbols() { add("and", ast::Operator::And)("or", ast::Operator::Or)("xor", ast::Operator::Xor); }
};
struct CompareSymbols : x3::symbols<ast::Operator> {
  CompareSymbols() {
    add("eq", ast::Operator::Eq)("ne", ast::Operator::Ne)("gt", ast::Operator::Gt)("ge", ast::Operator::Ge)(
        "lt", ast::Operator::Lt)("le", ast::Operator::Le);
  }
};
struct SumSymbols : x3::symbols<ast::Operator> {
  SumSymbols() { add("+", ast::Operator::Plus)("-", ast::Operator::Minus); }
};
struct ProductSymbols : x3::symbols<ast::Operator> {
  ProductSymbols() { add("*", ast::Operator::Times)("/", ast::Operator::Divide)("mod", ast::Operator::Modulo); }
};
struct PowerSymbols : x3::symbols<ast::Operator> {
  PowerSymbols() { add("**", ast::Operator::Power); }
};

// ---- rule IDs --------------------------------------------------------------------------
struct value_class;
struct expression_class;
struct compare_class;
struct sum_class;
struct product_class;
struct power_class;
struct bracketed_class;
struct parameter_class;
struct numbered_class;
struct named_class;
struct function_class;
struct atan_class;
struct exists_class;
struct signed_class;

// ---- rules -----------------------------------------------------------------------------
const x3::rule<value_class, ast::Expression> value = "a number, [expression], #parameter or function";
const x3::rule<expression_class, ast::Chain> expression = "an expression";
const x3::rule<compare_class, ast::Chain> compare = "an expression";
const x3::rule<sum_class, ast::Chain> sum = "an expression";
const x3::rule<product_class, ast::Chain> product = "an expression";
const x3::rule<power_class, ast::Chain> power = "an expression";
const x3::rule<bracketed_class, ast::Expression> bracketed = "[expression]";
const x3::rule<parameter_class, ast::Expression> parameter = "a parameter";
const x3::rule<numbered_class, ast::NumberedParameter> numbered = "a parameter number";
const x3::rule<named_class, ast::NamedParameter> named = "<name>";
const x3::rule<function_class, ast::Unary> function = "a function";
const x3::rule<atan_class, ast::Atan2> atan2 = "atan[y]/[x]";
const x3::rule<exists_class, ast::Unary> exists = "exists[#parameter]";
const x3::rule<signed_class, ast::Unary> signed_value = "a signed value";

// ---- grammar ---------------------------------------------------------------------------
const FunctionSymbols functions;
const SignSymbols signs;
const LogicSymbols logic_operators;
const CompareSymbols compare_operators;
const SumSymbols sum_operators;
const ProductSymbols product_operators;
const PowerSymbols power_operators;

const auto name_text = x3::lexeme[+(x3::char_ - '>')];

const auto value_def = number | bracketed | parameter | atan2 | exists | function | signed_value;
const auto bracketed_def = '[' > expression > ']';
const auto expression_def = compare >> *(logic_operators > compare);
const auto compare_def = sum >> *(compare_operators > sum);
const auto sum_def = product >> *(sum_operators > product);
const auto product_def = power >> *(product_operators > power);
const auto power_def = value >> *(power_operators > value);
const auto parameter_def = '#' > (named | numbered);
const auto named_def = '<' > name_text > '>';
const auto numbered_def = value;
const auto function_def = functions > '[' > expression > ']';
const auto atan2_def = x3::lit("atan") > '[' > expression > ']' > '/' > '[' > expression > ']';
const auto exists_def = x3::lit("exists") > x3::attr(ast::Function::Exists) > '[' > parameter > ']';
const auto signed_value_def = signs > value;

BOOST_SPIRIT_DEFINE(value, expression, compare, sum, product, power, bracketed, parameter, numbered, named, function,
                    atan2, exists, signed_value)

}  // namespace vc::gcode::parser
