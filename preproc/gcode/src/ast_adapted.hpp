// Fusion adaptations of the AST (kept out of ast.hpp, as in Spirit X3's rexpr example).
#pragma once

#include <boost/fusion/include/adapt_struct.hpp>

#include "vc/gcode/ast.hpp"

BOOST_FUSION_ADAPT_STRUCT(vc::gcode::ast::NamedParameter, name)
BOOST_FUSION_ADAPT_STRUCT(vc::gcode::ast::NumberedParameter, index)
BOOST_FUSION_ADAPT_STRUCT(vc::gcode::ast::Unary, function, operand)
BOOST_FUSION_ADAPT_STRUCT(vc::gcode::ast::Atan2, y, x)
BOOST_FUSION_ADAPT_STRUCT(vc::gcode::ast::Operation, op, operand)
BOOST_FUSION_ADAPT_STRUCT(vc::gcode::ast::Chain, first, rest)
