#include "openscenario/expression.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "openscenario/text_number.hpp"

namespace orch::openscenario {
namespace {

// Recursive descent, lowest precedence first: or, and, not, comparison, + -, * / %, unary -.
class Parser {
 public:
  Parser(std::string_view text, const ParameterLookup& lookup) : text_(text), lookup_(lookup) {}

  double parse() {
    const double value = disjunction();
    skip_space();
    if (pos_ < text_.size()) fail(fmt::format("unexpected \"{}\"", text_.substr(pos_)));
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw ExpressionError(fmt::format("in expression \"{}\" at character {}: {}", text_, pos_ + 1, message));
  }
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool accept(std::string_view token) {
    skip_space();
    if (text_.substr(pos_, token.size()) != token) return false;
    // Word operators must not be the start of a longer word ("order" is not "or").
    if (std::isalpha(static_cast<unsigned char>(token.front())) && pos_ + token.size() < text_.size() &&
        (std::isalnum(static_cast<unsigned char>(text_[pos_ + token.size()])) || text_[pos_ + token.size()] == '_'))
      return false;
    pos_ += token.size();
    return true;
  }
  void expect(std::string_view token) {
    if (!accept(token)) fail(fmt::format("expected \"{}\"", token));
  }
  static double truth(bool b) { return b ? 1.0 : 0.0; }

  double disjunction() {
    double left = conjunction();
    while (accept("or")) {
      const double right = conjunction();
      left = truth(left != 0.0 || right != 0.0);
    }
    return left;
  }
  double conjunction() {
    double left = negation();
    while (accept("and")) {
      const double right = negation();
      left = truth(left != 0.0 && right != 0.0);
    }
    return left;
  }
  double negation() {
    if (accept("not")) return truth(negation() == 0.0);
    return comparison();
  }
  double comparison() {
    const double left = sum();
    if (accept("==")) return truth(left == sum());
    if (accept("!=")) return truth(left != sum());
    if (accept("<=")) return truth(left <= sum());
    if (accept(">=")) return truth(left >= sum());
    if (accept("<")) return truth(left < sum());
    if (accept(">")) return truth(left > sum());
    return left;
  }
  double sum() {
    double left = product();
    for (;;) {
      if (accept("+")) left += product();
      else if (accept("-")) left -= product();
      else return left;
    }
  }
  double product() {
    double left = unary();
    for (;;) {
      if (accept("*")) {
        left *= unary();
      } else if (accept("/")) {
        const double right = unary();
        if (right == 0.0) fail("division by zero");
        left /= right;
      } else if (accept("%")) {
        const double right = unary();
        if (right == 0.0) fail("remainder of a division by zero");
        left = std::fmod(left, right);
      } else {
        return left;
      }
    }
  }
  double unary() {
    if (accept("-")) return -unary();
    if (accept("+")) return unary();
    return primary();
  }
  std::string_view word() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  double parameter() {
    const std::size_t start = pos_;
    const std::string_view name = word();
    if (name.empty()) fail("expected a parameter name after \"$\"");
    const auto value = lookup_(name);
    if (!value) {
      pos_ = start;
      fail(fmt::format("unknown parameter \"{}\"", name));
    }
    if (*value == "true") return 1.0;
    if (*value == "false") return 0.0;
    const auto number = parse_whole<double>(*value);
    if (!number) {
      pos_ = start;
      fail(fmt::format("parameter \"{}\" has the value \"{}\", not a number", name, *value));
    }
    return *number;
  }
  double call(std::string_view name) {
    static const std::map<std::string, std::pair<int, double (*)(double, double)>, std::less<>> functions = {
        {"sqrt", {1, [](double a, double) { return std::sqrt(a); }}},
        {"round", {1, [](double a, double) { return std::round(a); }}},
        {"floor", {1, [](double a, double) { return std::floor(a); }}},
        {"ceil", {1, [](double a, double) { return std::ceil(a); }}},
        {"abs", {1, [](double a, double) { return std::abs(a); }}},
        // -1 below zero, else 1 (sign(0) = 1), as the peer player esmini computes it.
        {"sign", {1, [](double a, double) { return a < 0 ? -1.0 : 1.0; }}},
        {"sin", {1, [](double a, double) { return std::sin(a); }}},
        {"cos", {1, [](double a, double) { return std::cos(a); }}},
        {"tan", {1, [](double a, double) { return std::tan(a); }}},
        {"asin", {1, [](double a, double) { return std::asin(a); }}},
        {"acos", {1, [](double a, double) { return std::acos(a); }}},
        {"atan", {1, [](double a, double) { return std::atan(a); }}},
        {"exp", {1, [](double a, double) { return std::exp(a); }}},
        {"log", {1, [](double a, double) { return std::log(a); }}},
        {"pow", {2, [](double a, double b) { return std::pow(a, b); }}},
        {"min", {2, [](double a, double b) { return std::min(a, b); }}},
        {"max", {2, [](double a, double b) { return std::max(a, b); }}},
    };
    const auto it = functions.find(name);
    if (it == functions.end()) {
      std::vector<std::string> names;
      for (const auto& [n, f] : functions) names.push_back(n);
      fail(fmt::format("unknown function \"{}\"{}", name, did_you_mean(name, names)));
    }
    expect("(");
    const double a = disjunction();
    double b = 0.0;
    if (it->second.first == 2) {
      expect(",");
      b = disjunction();
    }
    expect(")");
    const double result = it->second.second(a, b);
    if (!std::isfinite(result)) fail(fmt::format("{} gives no finite number here", name));
    return result;
  }
  double primary() {
    skip_space();
    if (pos_ >= text_.size()) fail("expected a value");
    const char c = text_[pos_];
    if (accept("(")) {
      const double value = disjunction();
      expect(")");
      return value;
    }
    if (c == '$') {
      ++pos_;
      return parameter();
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      double number = 0.0;
      const auto [end, ec] = std::from_chars(text_.data() + pos_, text_.data() + text_.size(), number);
      if (ec != std::errc()) fail("malformed number");
      pos_ = static_cast<std::size_t>(end - text_.data());
      return number;
    }
    if (std::isalpha(static_cast<unsigned char>(c))) {
      const std::size_t start = pos_;
      const std::string_view name = word();
      if (name == "true") return 1.0;
      if (name == "false") return 0.0;
      skip_space();
      // Not in the standard; real files use it and the peer player esmini defines it.
      if (name == "pi" && (pos_ >= text_.size() || text_[pos_] != '(')) return std::numbers::pi;
      if (pos_ < text_.size() && text_[pos_] == '(') return call(name);
      pos_ = start;
      fail(fmt::format("unexpected word \"{}\" (parameters are written $name)", name));
    }
    fail(fmt::format("unexpected \"{}\"", c));
  }

  std::string_view text_;
  const ParameterLookup& lookup_;
  std::size_t pos_ = 0;
};

}  // namespace

double evaluate_expression(std::string_view expression, const ParameterLookup& lookup) {
  return Parser(expression, lookup).parse();
}

std::optional<std::string> concatenate_expression(std::string_view expression, const ParameterLookup& lookup) {
  const auto trim = [](std::string_view t) {
    while (!t.empty() && std::isspace(static_cast<unsigned char>(t.front()))) t.remove_prefix(1);
    while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.remove_suffix(1);
    return t;
  };
  const auto is_word_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; };
  std::string out;
  bool bare_word = false;
  std::size_t start = 0;
  for (;;) {
    const std::size_t plus = expression.find('+', start);
    const std::string_view term = trim(expression.substr(start, plus == std::string_view::npos ? plus : plus - start));
    if (term.empty()) return std::nullopt;
    if (term.front() == '$') {
      const std::string_view name = term.substr(1);
      if (name.empty() || !std::all_of(name.begin(), name.end(), is_word_char)) return std::nullopt;
      const auto value = lookup(name);
      if (!value) throw ExpressionError(fmt::format("in expression \"{}\": unknown parameter \"{}\"", expression, name));
      out += *value;
    } else {
      if (!std::all_of(term.begin(), term.end(), is_word_char)) return std::nullopt;
      if (!parse_whole<double>(term) && term != "true" && term != "false") bare_word = true;
      out += term;
    }
    if (plus == std::string_view::npos) break;
    start = plus + 1;
  }
  // One term alone is no concatenation ("${Speed}" is a parameter without its '$').
  return bare_word && start > 0 ? std::optional(out) : std::nullopt;
}

std::string format_number(double value) {
  if (value == std::floor(value) && std::abs(value) < 1e15) return fmt::format("{}", static_cast<long long>(value));
  return fmt::format("{}", value);
}

}  // namespace orch::openscenario
