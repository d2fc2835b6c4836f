#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "solver/io/expression.hpp"

using refmap::Expression;

namespace {
double ev(const std::string& s, double x = 0, double y = 0, double t = 0) { return Expression(s).eval(x, y, t); }

std::string parse_error(const std::string& s) {
  try {
    Expression e(s);
  } catch (const std::invalid_argument& ex) {
    return ex.what();
  }
  return "";
}
}  // namespace

TEST(Expression, Arithmetic) {
  EXPECT_DOUBLE_EQ(ev("1+2*3"), 7.0);
  EXPECT_DOUBLE_EQ(ev("(1+2)*3"), 9.0);
  EXPECT_DOUBLE_EQ(ev("10/4/5"), 0.5);     // left-associative
  EXPECT_DOUBLE_EQ(ev("10-4-3"), 3.0);     // left-associative
  EXPECT_DOUBLE_EQ(ev("2*3^2"), 18.0);     // ^ binds tighter than *
  EXPECT_DOUBLE_EQ(ev("2^3^2"), 512.0);    // right-associative power
  EXPECT_DOUBLE_EQ(ev("-2^2"), -4.0);      // unary minus below power
  EXPECT_DOUBLE_EQ(ev("2^-1"), 0.5);       // signed exponent
  EXPECT_DOUBLE_EQ(ev("1 - -1"), 2.0);
  EXPECT_DOUBLE_EQ(ev("+3"), 3.0);
  EXPECT_DOUBLE_EQ(ev("--3"), 3.0);
  EXPECT_DOUBLE_EQ(ev("  ( ( 4 ) )  "), 4.0);
}

TEST(Expression, Numbers) {
  EXPECT_DOUBLE_EQ(ev("1e-3"), 1e-3);
  EXPECT_DOUBLE_EQ(ev("2.5E2"), 250.0);
  EXPECT_DOUBLE_EQ(ev("1e+2"), 100.0);
  EXPECT_DOUBLE_EQ(ev(".5"), 0.5);
  EXPECT_DOUBLE_EQ(ev("3."), 3.0);
  EXPECT_DOUBLE_EQ(ev("0.1"), 0.1);  // exact decimal conversion
}

TEST(Expression, VariablesAndConstants) {
  EXPECT_DOUBLE_EQ(ev("x", 2, 3, 4), 2.0);
  EXPECT_DOUBLE_EQ(ev("y", 2, 3, 4), 3.0);
  EXPECT_DOUBLE_EQ(ev("t", 2, 3, 4), 4.0);
  EXPECT_DOUBLE_EQ(ev("x*y+t", 2, 3, 4), 10.0);
  EXPECT_DOUBLE_EQ(ev("pi"), std::numbers::pi);
  EXPECT_DOUBLE_EQ(ev("e"), std::numbers::e);
  EXPECT_DOUBLE_EQ(ev("2*e"), 2 * std::numbers::e);
  Expression e("x^2 + y");
  EXPECT_DOUBLE_EQ(e(3, 1), 10.0);  // t defaults to 0
  EXPECT_DOUBLE_EQ(e.eval(-3, 1), 10.0);
  EXPECT_FALSE(e.uses_time());
  EXPECT_TRUE(Expression("sin(t)").uses_time());
  EXPECT_EQ(e.text(), "x^2 + y");
}

TEST(Expression, Functions) {
  const double pi = std::numbers::pi;
  EXPECT_NEAR(ev("sin(pi/2)"), 1.0, 1e-15);
  EXPECT_NEAR(ev("cos(pi)"), -1.0, 1e-15);
  EXPECT_NEAR(ev("tan(pi/4)"), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(ev("exp(1)"), std::numbers::e);
  EXPECT_DOUBLE_EQ(ev("log(e)"), 1.0);
  EXPECT_DOUBLE_EQ(ev("sqrt(16)"), 4.0);
  EXPECT_DOUBLE_EQ(ev("abs(-3.5)"), 3.5);
  EXPECT_DOUBLE_EQ(ev("tanh(0.5)"), std::tanh(0.5));
  EXPECT_DOUBLE_EQ(ev("atan2(1, 1)"), pi / 4);
  EXPECT_DOUBLE_EQ(ev("atan2(1, -1)"), 3 * pi / 4);  // argument order (y, x)
  EXPECT_DOUBLE_EQ(ev("min(3, 2)"), 2.0);
  EXPECT_DOUBLE_EQ(ev("max(3, 2)"), 3.0);
  EXPECT_DOUBLE_EQ(ev("pow(2, 10)"), 1024.0);
  EXPECT_DOUBLE_EQ(ev("log10(1000)"), 3.0);
  EXPECT_DOUBLE_EQ(ev("floor(-1.5) + ceil(1.2)"), 0.0);
  EXPECT_DOUBLE_EQ(ev("max(min(x, 1), -1)", 5), 1.0);
  // a typical initial condition
  const double x = 0.3, y = 0.7;
  EXPECT_NEAR(ev("sin(2*pi*x)*cos(2*pi*y)", x, y), std::sin(2 * pi * x) * std::cos(2 * pi * y), 1e-15);
  EXPECT_NEAR(ev("-cos(2*pi*x) * sin(2*pi*y) * exp(-8*pi^2*0.01*t)", x, y, 0.5),
              -std::cos(2 * pi * x) * std::sin(2 * pi * y) * std::exp(-8 * pi * pi * 0.01 * 0.5), 1e-15);
}

TEST(Expression, EmptyDefaultIsZero) {
  Expression e;
  EXPECT_TRUE(e.empty());
  EXPECT_EQ(e.eval(1, 2, 3), 0.0);
}

TEST(Expression, SyntaxErrorsReportPosition) {
  EXPECT_NE(parse_error("").find("empty"), std::string::npos);
  EXPECT_NE(parse_error("1+").find("position 3"), std::string::npos) << parse_error("1+");
  EXPECT_NE(parse_error("(1").find("expected ')'"), std::string::npos);
  EXPECT_NE(parse_error("1)").find("position 2"), std::string::npos) << parse_error("1)");
  EXPECT_NE(parse_error("1 2").find("position 3"), std::string::npos) << parse_error("1 2");
  EXPECT_NE(parse_error("2e").find("exponent"), std::string::npos);
  EXPECT_NE(parse_error("1 $ 2").find("position 3"), std::string::npos);
  EXPECT_NE(parse_error("x*").find("end of expression"), std::string::npos);
  EXPECT_NE(parse_error("()").find("position 2"), std::string::npos);
}

TEST(Expression, UnknownNamesAndArity) {
  const std::string z = parse_error("sin(z)");
  EXPECT_NE(z.find("position 5"), std::string::npos) << z;
  EXPECT_NE(z.find("unknown identifier 'z'"), std::string::npos) << z;
  EXPECT_NE(parse_error("foo(1)").find("unknown function 'foo'"), std::string::npos);
  EXPECT_NE(parse_error("sin(1, 2)").find("takes 1 argument, got 2"), std::string::npos);
  EXPECT_NE(parse_error("atan2(1)").find("takes 2 arguments, got 1"), std::string::npos);
  EXPECT_NE(parse_error("sin").find("needs an argument"), std::string::npos);
  EXPECT_NE(parse_error("X").find("unknown identifier"), std::string::npos);  // case-sensitive
}

TEST(Expression, DeepNestingIsAnErrorNotACrash) {
  std::string deep(500, '(');
  deep += '1';
  deep.append(500, ')');
  EXPECT_THROW(Expression{deep}, std::invalid_argument);
  // a long but shallow expression is fine
  std::string sum = "0";
  for (int i = 1; i <= 1000; ++i) {
    sum += '+';
    sum += std::to_string(i);
  }
  EXPECT_DOUBLE_EQ(Expression(sum).eval(0, 0), 500500.0);
}
