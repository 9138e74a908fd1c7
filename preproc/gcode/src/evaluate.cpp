#include "vc/gcode/evaluate.hpp"

#include <cmath>
#include <string>

namespace vc::gcode {
namespace {

constexpr double kDegree = M_PI / 180.0;
constexpr double kEqualTolerance = 0.0001;  // LinuxCNC's TOLERANCE_EQUAL for EQ and NE

class Evaluator {
 public:
  Evaluator(const Parameters& parameters, int offset) : parameters_(parameters), offset_(offset) {}

  double operator()(double v) const { return v; }
  double operator()(const ast::NamedParameter& p) const { return parameters_.get(p.name, offset_); }
  double operator()(const ast::NumberedParameter& p) const {
    return parameters_.get(boost::apply_visitor(*this, p.index), offset_);
  }
  double operator()(const ast::Atan2& a) const {
    return std::atan2(boost::apply_visitor(*this, a.y), boost::apply_visitor(*this, a.x)) / kDegree;
  }
  double operator()(const ast::Unary& u) const {
    using F = ast::Function;
    if (u.function == F::Exists) {  // a numbered parameter exists if its number is in range (LinuxCNC)
      if (const auto* named = boost::get<ast::NamedParameter>(&u.operand))
        return parameters_.exists(named->name) ? 1 : 0;
      const auto& numbered = boost::get<boost::spirit::x3::forward_ast<ast::NumberedParameter>>(u.operand).get();
      const double n = boost::apply_visitor(*this, numbered.index);
      return std::round(n) >= 1 && std::round(n) < Parameters::kCount ? 1 : 0;
    }
    const double v = boost::apply_visitor(*this, u.operand);
    switch (u.function) {
      case F::Minus:
        return -v;
      case F::Plus:
        return v;
      case F::Abs:
        return std::abs(v);
      case F::Acos:
        check(v >= -1 && v <= 1, "ACOS of a value outside [-1, 1]");
        return std::acos(v) / kDegree;
      case F::Asin:
        check(v >= -1 && v <= 1, "ASIN of a value outside [-1, 1]");
        return std::asin(v) / kDegree;
      case F::Cos:
        return std::cos(v * kDegree);
      case F::Exp:
        return std::exp(v);
      case F::Fix:
        return std::floor(v);
      case F::Fup:
        return std::ceil(v);
      case F::Round:
        return std::round(v);
      case F::Ln:
        check(v > 0, "LN of a value that is not positive");
        return std::log(v);
      case F::Sin:
        return std::sin(v * kDegree);
      case F::Sqrt:
        check(v >= 0, "SQRT of a negative value");
        return std::sqrt(v);
      case F::Tan:
        return std::tan(v * kDegree);
      case F::Exists:
        break;
    }
    return v;
  }
  double operator()(const ast::Chain& c) const {
    double left = boost::apply_visitor(*this, c.first);
    for (const ast::Operation& o : c.rest) left = apply(o.op, left, boost::apply_visitor(*this, o.operand));
    return left;
  }

 private:
  void check(bool ok, const char* message) const {
    if (!ok) throw SyntaxError(offset_, message);
  }

  double apply(ast::Operator op, double a, double b) const {
    using O = ast::Operator;
    switch (op) {
      case O::Power:
        check(a >= 0 || b == std::floor(b), "a negative number raised to a non-integer power");
        return std::pow(a, b);
      case O::Times:
        return a * b;
      case O::Divide:
        check(b != 0, "division by zero");
        return a / b;
      case O::Modulo: {
        check(b != 0, "MOD by zero");
        const double r = std::fmod(a, b);
        return r < 0 ? r + std::abs(b) : r;  // as LinuxCNC: never negative
      }
      case O::Plus:
        return a + b;
      case O::Minus:
        return a - b;
      case O::Eq:
        return std::abs(a - b) < kEqualTolerance ? 1 : 0;
      case O::Ne:
        return std::abs(a - b) < kEqualTolerance ? 0 : 1;
      case O::Gt:
        return a > b ? 1 : 0;
      case O::Ge:
        return a >= b ? 1 : 0;
      case O::Lt:
        return a < b ? 1 : 0;
      case O::Le:
        return a <= b ? 1 : 0;
      case O::And:
        return (a != 0 && b != 0) ? 1 : 0;
      case O::Or:
        return (a != 0 || b != 0) ? 1 : 0;
      case O::Xor:
        return ((a != 0) != (b != 0)) ? 1 : 0;
    }
    return 0;
  }

  const Parameters& parameters_;
  int offset_;
};

}  // namespace

double evaluate(const ast::Expression& expression, const Parameters& parameters, int offset) {
  const double v = boost::apply_visitor(Evaluator(parameters, offset), expression);
  if (!std::isfinite(v)) throw SyntaxError(offset, "the value is not a finite number");
  return v;
}

void apply_assignments(const Block& block, Parameters& parameters) {
  if (block.assignments.empty()) return;
  // All values first, with the parameters as they were before the line.
  thread_local std::vector<double> values, numbers;
  values.clear();
  numbers.clear();
  for (const Assignment& a : block.assignments) {
    values.push_back(evaluate(a.value, parameters, a.begin));
    if (const auto* numbered = boost::get<boost::spirit::x3::forward_ast<ast::NumberedParameter>>(&a.target))
      numbers.push_back(evaluate(numbered->get().index, parameters, a.begin));
    else
      numbers.push_back(0);
  }
  for (std::size_t i = 0; i < block.assignments.size(); ++i) {
    const Assignment& a = block.assignments[i];
    if (const auto* named = boost::get<ast::NamedParameter>(&a.target))
      parameters.set(named->name, values[i]);
    else
      parameters.set(numbers[i], values[i], a.begin);
  }
}

}  // namespace vc::gcode
