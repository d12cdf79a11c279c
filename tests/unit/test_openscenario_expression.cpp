// OpenSCENARIO "${...}" expressions and "$name" substitution.
#include <gtest/gtest.h>

#include <cmath>

#include "openscenario/expression.hpp"
#include "openscenario/parameters.hpp"

namespace orch::openscenario {
namespace {

double eval(std::string_view text) {
  ParameterScope scope;
  scope.set("speed", "double", "60.0");
  scope.set("lane", "integer", "-1");
  scope.set("on", "boolean", "true");
  scope.set("name", "string", "car");
  return evaluate_expression(text, [&](std::string_view n) { return scope.value(n); });
}

TEST(OpenScenarioExpression, ArithmeticFollowsPrecedenceAndParentheses) {
  EXPECT_DOUBLE_EQ(eval("1 + 2 * 3"), 7.0);
  EXPECT_DOUBLE_EQ(eval("(1 + 2) * 3"), 9.0);
  EXPECT_DOUBLE_EQ(eval("10 - 4 - 3"), 3.0);
  EXPECT_DOUBLE_EQ(eval("12 / 4 / 3"), 1.0);
  EXPECT_DOUBLE_EQ(eval("7 % 4"), 3.0);
  EXPECT_DOUBLE_EQ(eval("-2 * -3"), 6.0);
  EXPECT_DOUBLE_EQ(eval("- (2 + 3)"), -5.0);
  EXPECT_DOUBLE_EQ(eval("1.5e1 + .5"), 15.5);
}

TEST(OpenScenarioExpression, ParametersAndTheAlksForms) {
  // From the OSC-ALKS files: ${$Ego_InitSpeed_Ve0_kph / 3.6}, ${-$x}, nested parentheses.
  EXPECT_NEAR(eval("$speed / 3.6"), 60.0 / 3.6, 1e-12);
  EXPECT_DOUBLE_EQ(eval("-$speed"), -60.0);
  EXPECT_NEAR(eval("30.0 + (-10.0 * ($speed / 3.6))"), 30.0 - 600.0 / 3.6, 1e-12);
  EXPECT_DOUBLE_EQ(eval("$lane * 2"), -2.0);
  EXPECT_DOUBLE_EQ(eval("$on and not false"), 1.0);
}

TEST(OpenScenarioExpression, FunctionsComparisonsAndLogic) {
  EXPECT_DOUBLE_EQ(eval("sqrt(16)"), 4.0);
  EXPECT_DOUBLE_EQ(eval("pow(2, 10)"), 1024.0);
  EXPECT_DOUBLE_EQ(eval("round(2.5)"), 3.0);
  EXPECT_DOUBLE_EQ(eval("floor(-1.5) + ceil(1.2)"), 0.0);
  EXPECT_DOUBLE_EQ(eval("max(1, min(5, 3))"), 3.0);
  EXPECT_DOUBLE_EQ(eval("1 < 2 and 3 >= 3"), 1.0);
  EXPECT_DOUBLE_EQ(eval("1 == 2 or 2 != 2"), 0.0);
  EXPECT_DOUBLE_EQ(eval("not 1 > 2"), 1.0);
  EXPECT_DOUBLE_EQ(eval("true + true"), 2.0);
}

TEST(OpenScenarioExpression, EveryFunctionOfTheStandardAndWhatThePeerAdds) {
  // 1.2's functions, from real files: sign, abs, min, max with parameters.
  EXPECT_DOUBLE_EQ(eval("sign(-$speed)"), -1.0);
  EXPECT_DOUBLE_EQ(eval("sign(0.5)"), 1.0);
  EXPECT_DOUBLE_EQ(eval("sign(0)"), 1.0);  // as the peer player esmini: -1 below zero, else 1
  EXPECT_DOUBLE_EQ(eval("abs($lane) * max(2, 3) - min(1, -1)"), 4.0);
  EXPECT_NEAR(eval("sin(0) + cos(0) + tan(0) + asin(1) + acos(1) + atan(0)"), 1.0 + std::acos(0.0), 1e-12);
  // pi: not in the standard; the peer defines it and parking_demo.xosc uses ${pi}.
  EXPECT_DOUBLE_EQ(eval("pi"), std::acos(-1.0));
  EXPECT_DOUBLE_EQ(eval("2 * pi / pi"), 2.0);
}

TEST(OpenScenarioParameters, TheNamesThePeerJoinsWithPlus) {
  // cut-in.xosc names a condition "${BrakeCondition_HWT + _ + $HeadwayTime_Brake}"; the peer
  // player esmini joins the terms as text (parameters by their value).
  ParameterScope scope;
  scope.set("HeadwayTime_Brake", "double", "0.7");
  EXPECT_EQ(substitute("${BrakeCondition_HWT + _ + $HeadwayTime_Brake}", scope), "BrakeCondition_HWT_0.7");
  EXPECT_EQ(substitute("${1 + 2}", scope), "3");  // numbers still add
  EXPECT_THROW((void)substitute("${Speed}", scope), ExpressionError);  // a lone word is a parameter without '$'
  EXPECT_THROW((void)substitute("${a + b * 2}", scope), ExpressionError);
  EXPECT_THROW((void)substitute("${a + $missing}", scope), ExpressionError);
}

TEST(OpenScenarioExpression, ErrorsSayWhatAndWhere) {
  const auto message = [](std::string_view text) {
    try {
      (void)eval(text);
    } catch (const ExpressionError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("$sped / 3.6").find("unknown parameter \"sped\""), std::string::npos);
  EXPECT_NE(message("sqrtt(4)").find("did you mean \"sqrt\""), std::string::npos);
  EXPECT_NE(message("1 / 0").find("division by zero"), std::string::npos);
  EXPECT_NE(message("(1 + 2").find("expected \")\""), std::string::npos);
  EXPECT_NE(message("1 + 2 3").find("at character"), std::string::npos);
  EXPECT_NE(message("$name + 1").find("not a number"), std::string::npos);
  EXPECT_NE(message("sqrt(-1)").find("no finite number"), std::string::npos);
}

TEST(OpenScenarioParameters, SubstitutionOfReferencesAndExpressions) {
  ParameterScope outer;
  outer.set("model", "string", "car");
  outer.set("v", "double", "2.5");
  ParameterScope inner(&outer);
  inner.set("v", "double", "4");
  EXPECT_EQ(substitute("$model", inner), "car");
  EXPECT_EQ(substitute("${$v * 2}", inner), "8");  // the inner declaration hides the outer
  EXPECT_EQ(substitute("${$v * 2}", outer), "5");
  EXPECT_EQ(substitute("${1 / 3}", outer), "0.3333333333333333");
  EXPECT_EQ(substitute("plain", outer), "plain");
  EXPECT_THROW((void)substitute("$missing", outer), ExpressionError);
}

TEST(OpenScenarioParameters, ValuesAreCheckedAgainstTheirType) {
  EXPECT_EQ(check_parameter_value("integer", "-4"), "");
  EXPECT_EQ(check_parameter_value("int", "-4"), "");  // 1.2's name of the type
  EXPECT_EQ(parameter_type("int"), "integer");
  EXPECT_EQ(parameter_type("unsignedInt"), "unsignedInt");
  EXPECT_EQ(parameter_type("float"), std::nullopt);
  EXPECT_NE(check_parameter_value("unsignedInt", "-1"), "");
  EXPECT_NE(check_parameter_value("integer", "4.5"), "");
  EXPECT_NE(check_parameter_value("unsignedShort", "70000"), "");
  EXPECT_EQ(check_parameter_value("double", "1e3"), "");
  EXPECT_NE(check_parameter_value("double", "fast"), "");
  EXPECT_EQ(check_parameter_value("boolean", "false"), "");
  EXPECT_NE(check_parameter_value("boolean", "yes"), "");
}

}  // namespace
}  // namespace orch::openscenario
