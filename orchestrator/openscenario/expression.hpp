#pragma once
// OpenSCENARIO 1.x parameter expressions: the text inside "${...}". Numbers, parameter
// references ($name), + - * / %, parentheses, unary minus, comparisons (== != < <= > >=),
// not / and / or, true / false, and the functions sqrt, round, floor, ceil, pow, abs, min,
// max, sin, cos, tan, asin, acos, atan, exp, log. Booleans are 1 / 0 in arithmetic.
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

// Formats a number as the value of a parameter: integers without a fraction, others with
// the shortest text that reads back as the same double.
std::string format_number(double value);

}  // namespace orch::openscenario
