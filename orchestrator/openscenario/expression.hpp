#pragma once
// OpenSCENARIO 1.x parameter expressions: the text inside "${...}". Numbers, parameter
// references ($name), + - * / %, parentheses, unary minus, comparisons (== != < <= > >=),
// not / and / or, true / false, and the functions of the standard: round, floor, ceil, sqrt,
// pow (1.1), sin, cos, tan, asin, acos, atan, sign, abs, min, max (1.2); exp and log besides.
// Booleans are 1 / 0 in arithmetic. Not in the standard, as the peer player esmini reads
// real files: the constant pi, and sign(0) = 1.
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace orch::openscenario {

// A problem in an expression; the message says what and where (character position).
class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Value of a parameter by name (without '$'), or nullopt when it is not declared. The
// value is the parameter's text; it must read as a number or a boolean here.
using ParameterLookup = std::function<std::optional<std::string>(std::string_view name)>;

// Evaluates `expression` (the text between "${" and "}"). Throws ExpressionError.
double evaluate_expression(std::string_view expression, const ParameterLookup& lookup);

// The peer player esmini's reading of an expression that is no number: terms joined by '+'
// of which some are bare words ("${Brake_ + $Time}" -> "Brake_0.7", parameters by their
// text). nullopt when `expression` is not of that form. Not in the standard; real files
// use it for names.
std::optional<std::string> concatenate_expression(std::string_view expression, const ParameterLookup& lookup);

// Formats a number as the value of a parameter: integers without a fraction, others with
// the shortest text that reads back as the same double.
std::string format_number(double value);

}  // namespace orch::openscenario
