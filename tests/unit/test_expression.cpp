// The user expression language (seed 001 section 3.4): compiler, constant
// folding, interpreter (float and double) and error reporting. Expected
// values come from direct C++ evaluation of the same formulas.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "host/expr/program.hpp"
#include "kernels/expr/interpreter.hpp"

namespace mfsd::expr {
namespace {

// Table 1 of seed 001.
const VariableTable kVars{{"x0", "y0", "z0", "x", "y", "z", "ux", "uy", "uz", "t", "dt", "dx"}};
constexpr int kNumVars = 12;

template <class Real>
struct Outcome {
  Status status;
  Real value;
  int pc;
};

// Evaluates with the named variables set (the others 0) through the kernel interpreter.
template <class Real>
Outcome<Real> run(const Program& p, const std::vector<std::pair<std::string, double>>& values = {}) {
  std::array<Real, kNumVars> vars{};
  for (const auto& [name, v] : values) vars[kVars.slot(name)] = static_cast<Real>(v);
  Outcome<Real> o{Status::ok, Real(-12345), -1};
  o.status = evaluate(p.host_view<Real>(), vars.data(), &o.value, &o.pc);
  return o;
}

Program comp(const std::string& e, const std::string& locals = "", const std::map<std::string, double>& c = {}) {
  return compile(e, kVars, c, locals);
}

// Value of `e` in double; fails the test unless the status is ok.
double value(const std::string& e, const std::vector<std::pair<std::string, double>>& values = {},
             const std::string& locals = "") {
  const Outcome<double> o = run<double>(comp(e, locals), values);
  EXPECT_EQ(o.status, Status::ok) << e;
  return o.value;
}

// Column and message of the compile error of `e`; fails the test when it compiles.
ExpressionError compile_error(const std::string& e, const std::string& locals = "",
                              const std::map<std::string, double>& c = {}) {
  try {
    comp(e, locals, c);
  } catch (const ExpressionError& err) {
    return err;
  }
  ADD_FAILURE() << "expected a compile error for \"" << e << "\" with locals \"" << locals << "\"";
  return ExpressionError("", "", -1, "");
}

// Checks that `e` (with `locals`) fails to compile at `column` with a message containing `fragment`.
void expect_compile_error(const std::string& e, const std::string& locals, int column, const std::string& fragment) {
  const ExpressionError err = compile_error(e, locals);
  EXPECT_EQ(err.column(), column) << err.what();
  EXPECT_NE(std::string(err.what()).find(fragment), std::string::npos) << err.what();
}

std::string literal(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

bool single_push(const Program& p, double v) {
  return p.is_constant() && p.code().size() == 1 && p.code()[0].op == Op::push_const && p.constant_value() == v;
}

// ------------------------------------------------------------------ syntax and precedence

TEST(Expression, Numbers) {
  EXPECT_EQ(value("1"), 1.0);
  EXPECT_EQ(value("1.5"), 1.5);
  EXPECT_EQ(value(".5"), 0.5);
  EXPECT_EQ(value("1e-3"), 1e-3);
  EXPECT_EQ(value("2.5E+6"), 2.5e6);
  EXPECT_EQ(value("3E2"), 300.0);
  EXPECT_EQ(value("7."), 7.0);
  EXPECT_DOUBLE_EQ(value("pi"), M_PI);
}

TEST(Expression, PrecedenceAndAssociativityFolded) {
  EXPECT_EQ(value("2+3*4^2"), 2 + 3 * 16);
  EXPECT_EQ(value("2^3^2"), 512.0);
  EXPECT_EQ(value("(2^3)^2"), 64.0);
  EXPECT_EQ(value("-2^2"), -4.0);
  EXPECT_EQ(value("2^-1"), 0.5);
  EXPECT_EQ(value("1-2-3"), -4.0);
  EXPECT_EQ(value("8/4/2"), 1.0);
  EXPECT_EQ(value("1<2==1"), 1.0);
  EXPECT_EQ(value("2*-3"), -6.0);
  EXPECT_EQ(value("--2"), 2.0);
  EXPECT_EQ(value("+2"), 2.0);
  EXPECT_EQ(value("1+2<4 and 2>1 or 0"), 1.0);
  EXPECT_EQ(value("0 or 0 and 1"), 0.0);  // and binds tighter than or
  EXPECT_EQ(value("1 or 0 and 0"), 1.0);
}

TEST(Expression, PrecedenceAndAssociativityInterpreted) {
  // The same shapes with variables, so the interpreter (not the folder) computes them.
  const std::vector<std::pair<std::string, double>> v{{"x0", 2}, {"y0", 3}, {"z0", 4}, {"t", 8}};
  EXPECT_EQ(value("x0+y0*z0^x0", v), 2 + 3 * 16);
  EXPECT_EQ(value("x0^y0^x0", v), 512.0);
  EXPECT_EQ(value("(x0^y0)^x0", v), 64.0);
  EXPECT_EQ(value("-x0^2", v), -4.0);
  EXPECT_EQ(value("x0^-1", v), 0.5);
  EXPECT_EQ(value("x0-y0-z0", v), -5.0);
  EXPECT_EQ(value("t/z0/x0", v), 1.0);
  EXPECT_EQ(value("x0<y0==1", v), 1.0);
  EXPECT_EQ(value("x0*-y0", v), -6.0);
  EXPECT_EQ(value("--x0", v), 2.0);
  EXPECT_EQ(value("x0 < y0 and y0 < x0 or z0 == 4", v), 1.0);
  EXPECT_EQ(value("0*x0 or 0*x0 and 1", v), 0.0);
  EXPECT_EQ(value("x0 or 0*x0 and 0", v), 1.0);
  EXPECT_EQ(value("y0 - x0 * (z0 - t) / x0", v), 3 - 2 * (4 - 8) / 2.0);
}

// ------------------------------------------------------------------ functions

TEST(Expression, FunctionsMatchTheCLibrary) {
  struct Case {
    const char* name;
    std::function<double(double)> f;
    std::vector<double> args;
  };
  const std::vector<Case> cases = {
      {"sin", [](double x) { return std::sin(x); }, {-2.5, 0.0, 0.3, 1.0, 7.0}},
      {"cos", [](double x) { return std::cos(x); }, {-2.5, 0.0, 0.3, 1.0, 7.0}},
      {"tan", [](double x) { return std::tan(x); }, {-1.2, 0.0, 0.3, 1.0}},
      {"cot", [](double x) { return std::cos(x) / std::sin(x); }, {-1.2, 0.3, 1.0, 3.0}},
      {"sinh", [](double x) { return std::sinh(x); }, {-3.0, 0.0, 0.5, 2.0}},
      {"cosh", [](double x) { return std::cosh(x); }, {-3.0, 0.0, 0.5, 2.0}},
      {"tanh", [](double x) { return std::tanh(x); }, {-3.0, 0.0, 0.5, 2.0}},
      {"coth", [](double x) { return std::cosh(x) / std::sinh(x); }, {-3.0, 0.5, 2.0, 10.0}},
      {"exp", [](double x) { return std::exp(x); }, {-3.0, 0.0, 0.5, 20.0}},
      {"sqrt", [](double x) { return std::sqrt(x); }, {0.0, 0.25, 2.0, 1e6}},
      {"abs", [](double x) { return std::fabs(x); }, {-3.5, 0.0, 2.0}},
      {"log", [](double x) { return std::log10(x); }, {0.001, 1.0, 10.0, 42.0}},
      {"ln", [](double x) { return std::log(x); }, {0.001, 1.0, 2.718281828, 42.0}},
      {"asin", [](double x) { return std::asin(x); }, {-1.0, -0.3, 0.0, 0.7, 1.0}},
      {"acos", [](double x) { return std::acos(x); }, {-1.0, -0.3, 0.0, 0.7, 1.0}},
      {"atan", [](double x) { return std::atan(x); }, {-100.0, -0.3, 0.0, 0.7, 5.0}},
      {"floor", [](double x) { return std::floor(x); }, {-2.5, -2.0, 0.0, 0.7, 3.0}},
      {"ceil", [](double x) { return std::ceil(x); }, {-2.5, -2.0, 0.0, 0.7, 3.0}},
  };
  for (const Case& c : cases) {
    const Program interpreted = comp(std::string(c.name) + "(x0)");
    for (double a : c.args) {
      const double expected = c.f(a);
      EXPECT_NEAR(run<double>(interpreted, {{"x0", a}}).value, expected, 1e-14 * (1 + std::fabs(expected)))
          << c.name << "(" << a << ")";
      const Program folded = comp(std::string(c.name) + "(" + literal(a) + ")");
      ASSERT_TRUE(folded.is_constant()) << c.name;
      EXPECT_NEAR(folded.constant_value(), expected, 1e-14 * (1 + std::fabs(expected))) << c.name << "(" << a << ")";
    }
  }
}

TEST(Expression, TwoArgumentFunctionsMatchTheCLibrary) {
  struct Case {
    const char* name;
    std::function<double(double, double)> f;
    std::vector<std::pair<double, double>> args;
  };
  const std::vector<Case> cases = {
      {"pow",
       [](double a, double b) { return std::pow(a, b); },
       {{2, 10}, {-2, 3}, {-2, -2}, {0, 0}, {2.5, 0.5}, {0, 2}}},
      {"min", [](double a, double b) { return std::fmin(a, b); }, {{1, 2}, {2, 1}, {-1, -1}}},
      {"max", [](double a, double b) { return std::fmax(a, b); }, {{1, 2}, {2, 1}, {-1, -1}}},
      {"atan2", [](double a, double b) { return std::atan2(a, b); }, {{1, 1}, {1, -1}, {-1, -1}, {0, -1}, {0, 0}}},
  };
  for (const Case& c : cases) {
    const Program p = comp(std::string(c.name) + "(x0, y0)");
    for (const auto& [a, b] : c.args) {
      const double expected = c.f(a, b);
      EXPECT_NEAR(run<double>(p, {{"x0", a}, {"y0", b}}).value, expected, 1e-14 * (1 + std::fabs(expected)))
          << c.name << "(" << a << ", " << b << ")";
      const Program folded = comp(std::string(c.name) + "(" + literal(a) + ", " + literal(b) + ")");
      ASSERT_TRUE(folded.is_constant());
      EXPECT_NEAR(folded.constant_value(), expected, 1e-14 * (1 + std::fabs(expected))) << c.name;
    }
  }
  EXPECT_EQ(value("x0^y0", {{"x0", -2}, {"y0", 3}}), -8.0);
}

// ------------------------------------------------------------------ logic

TEST(Expression, ComparisonsGiveOneOrZero) {
  const std::vector<std::pair<std::string, std::function<bool(double, double)>>> ops = {
      {"<", [](double a, double b) { return a < b; }},   {">", [](double a, double b) { return a > b; }},
      {"<=", [](double a, double b) { return a <= b; }}, {">=", [](double a, double b) { return a >= b; }},
      {"==", [](double a, double b) { return a == b; }}, {"!=", [](double a, double b) { return a != b; }},
  };
  for (const auto& [op, f] : ops) {
    const Program p = comp("x0 " + op + " y0");
    for (double a : {-1.0, 0.0, 2.0})
      for (double b : {-1.0, 0.0, 2.0}) EXPECT_EQ(run<double>(p, {{"x0", a}, {"y0", b}}).value, f(a, b) ? 1.0 : 0.0);
  }
}

TEST(Expression, AndOrTruthTablesAndShortCircuit) {
  const Program a = comp("x0 and y0");
  const Program o = comp("x0 or y0");
  for (double x : {0.0, 2.0, -0.5})
    for (double y : {0.0, 3.0}) {
      EXPECT_EQ(run<double>(a, {{"x0", x}, {"y0", y}}).value, (x != 0 && y != 0) ? 1.0 : 0.0);
      EXPECT_EQ(run<double>(o, {{"x0", x}, {"y0", y}}).value, (x != 0 || y != 0) ? 1.0 : 0.0);
    }
  // The right side must not run when the left decides.
  const Program guard = comp("x0!=0 and 1/x0>2");
  const Outcome<double> r0 = run<double>(guard, {{"x0", 0.0}});
  EXPECT_EQ(r0.status, Status::ok);
  EXPECT_EQ(r0.value, 0.0);
  EXPECT_EQ(run<double>(guard, {{"x0", 0.25}}).value, 1.0);
  EXPECT_EQ(run<double>(guard, {{"x0", 1.0}}).value, 0.0);
  const Program either = comp("x0==0 or 1/x0>2");
  const Outcome<double> r1 = run<double>(either, {{"x0", 0.0}});
  EXPECT_EQ(r1.status, Status::ok);
  EXPECT_EQ(r1.value, 1.0);
  EXPECT_EQ(run<double>(either, {{"x0", 4.0}}).value, 0.0);
  EXPECT_NE(guard.disassemble().find("and_jump"), std::string::npos);
  EXPECT_NE(either.disassemble().find("or_jump"), std::string::npos);
}

TEST(Expression, IfIsLazyAndNestable) {
  const Program p = comp("if(x0>0, sqrt(x0), 0)");
  const Outcome<double> neg = run<double>(p, {{"x0", -1.0}});
  EXPECT_EQ(neg.status, Status::ok);
  EXPECT_EQ(neg.value, 0.0);
  EXPECT_EQ(run<double>(p, {{"x0", 4.0}}).value, 2.0);

  const Program nested = comp("if(x0<0, -1, if(x0<1, 10*x0, if(x0<2, 100, 1000)))");
  auto reference = [](double x) { return x < 0 ? -1.0 : (x < 1 ? 10 * x : (x < 2 ? 100.0 : 1000.0)); };
  for (double x : {-3.0, 0.0, 0.5, 1.0, 1.5, 2.0, 7.0}) EXPECT_EQ(run<double>(nested, {{"x0", x}}).value, reference(x));

  const Program in_condition = comp("if(if(x0>0, x0, 0) > 1, 1, 2) + 1");
  EXPECT_EQ(run<double>(in_condition, {{"x0", 3.0}}).value, 2.0);
  EXPECT_EQ(run<double>(in_condition, {{"x0", -3.0}}).value, 3.0);
}

// ------------------------------------------------------------------ skip

TEST(Expression, SkipLeavesTheTargetUntouched) {
  for (const char* e : {"if(x0<0.0, 0.0, skip)", "if(x0<0.0, 0.0, Skip)", "if(x0>=0, (skip), 0)"}) {
    const Program p = comp(e);
    EXPECT_TRUE(p.may_skip()) << e;
    const Outcome<double> s = run<double>(p, {{"x0", 1.0}});
    EXPECT_EQ(s.status, Status::skipped) << e;
    EXPECT_EQ(s.value, -12345.0) << e;  // untouched
    const Outcome<double> v = run<double>(p, {{"x0", -1.0}});
    EXPECT_EQ(v.status, Status::ok) << e;
    EXPECT_EQ(v.value, 0.0) << e;
  }
  const Program nested = comp("if(x0<0, 1, if(t>0, skip, 2))");
  EXPECT_EQ(run<double>(nested, {{"x0", 1.0}, {"t", 1.0}}).status, Status::skipped);
  EXPECT_EQ(run<double>(nested, {{"x0", 1.0}, {"t", 0.0}}).value, 2.0);
  EXPECT_FALSE(comp("if(x0<0, 1, 2)").may_skip());
  EXPECT_THROW(nested.evaluate_host(std::array<double, kNumVars>{1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0}.data()),
               ExpressionError);
}

TEST(Expression, MisplacedSkipIsACompileError) {
  expect_compile_error("1 + skip", "", 5, "'skip' may only be a branch");
  expect_compile_error("pow(skip,2)", "", 5, "'skip' may only be a branch");
  expect_compile_error("if(skip,1,2)", "", 4, "'skip' may only be a branch");
  expect_compile_error("skip", "", 1, "'skip' may only be a branch");
  expect_compile_error("-skip", "", 2, "'skip' may only be a branch");
  expect_compile_error("if(x0, +skip, 1)", "", 9, "'skip' may only be a branch");
  expect_compile_error("if(x0, skip, 1) * 2", "", 8, "'skip' may only be a branch");
  expect_compile_error("if(x0, 1 + if(y0, skip, 1), 2)", "", 19, "'skip' may only be a branch");
  expect_compile_error("x0 and if(y0, skip, 1)", "", 15, "'skip' may only be a branch");
  expect_compile_error("a", "a=if(x0, skip, 1)", 10, "'skip' is not allowed in a local definition");
}

// ------------------------------------------------------------------ locals

TEST(Expression, ConstantLocalsFold) {
  const Program p = comp("cs*kw + L0", "L0=0.2; kw=9.375; cs=57.0");
  EXPECT_TRUE(single_push(p, 57.0 * 9.375 + 0.2));
  EXPECT_EQ(p.n_locals(), 0);
  const Program chained = comp("b", "a=2; b=a*a+pi;");  // trailing ';'
  EXPECT_TRUE(single_push(chained, 4 + M_PI));
}

TEST(Expression, RunTimeLocals) {
  const Program p = comp("g*2 + kw", "kw=9.375; f=kw*x0; g=f+y0;");
  EXPECT_EQ(p.n_locals(), 2);
  EXPECT_FALSE(p.is_constant());
  EXPECT_NE(p.disassemble().find("store_local"), std::string::npos);
  auto reference = [](double x0, double y0) { return (9.375 * x0 + y0) * 2 + 9.375; };
  for (double x : {-1.0, 0.0, 0.3})
    for (double y : {0.0, 2.0}) EXPECT_DOUBLE_EQ(run<double>(p, {{"x0", x}, {"y0", y}}).value, reference(x, y));

  // A run-time local the expression does not use is not computed.
  const Program unused = comp("x0 + 1", "r=sqrt(y0)");
  EXPECT_EQ(unused.disassemble().find("store_local"), std::string::npos);
  EXPECT_EQ(run<double>(unused, {{"x0", 1.0}, {"y0", -1.0}}).status, Status::ok);
  // One used only through another local is computed.
  const Program indirect = comp("b", "a=x0*2; b=a+1");
  EXPECT_EQ(run<double>(indirect, {{"x0", 3.0}}).value, 7.0);
}

TEST(Expression, BadLocalDefinitions) {
  expect_compile_error("1", "L0 0.2", 4, "expected '=' after the local name 'L0'");
  expect_compile_error("1", "=1", 1, "expected a local name");
  expect_compile_error("1", "a=1; a=2", 6, "'a' is already defined at column 1");
  expect_compile_error("1", "x0=1", 1, "would shadow the variable 'x0'");
  expect_compile_error("1", "sin=1", 1, "would shadow the function 'sin'");
  expect_compile_error("1", "pi=3", 1, "'pi' is reserved");
  expect_compile_error("1", "if=3", 1, "'if' is reserved");
  expect_compile_error("1", "a=", 3, "expected the value of local 'a'");
  expect_compile_error("1", "a=1 b=2", 5, "expected ';' or the end of the locals");
  expect_compile_error("1", "a=b; b=1", 3, "unknown name 'b'");  // only earlier locals are visible
  expect_compile_error("1", "a=sqrt(-4)", 3, "domain error");
  {
    const ExpressionError err = compile_error("1", "E=3", {{"E", 2.0}});
    EXPECT_EQ(err.column(), 1);
    EXPECT_NE(std::string(err.what()).find("would shadow the constant 'E'"), std::string::npos);
  }
  const ExpressionError err = compile_error("1", "kw=9.375; f=kw*; g=1");
  EXPECT_EQ(err.column(), 16);
  EXPECT_EQ(std::string(err.what()),
            "in locals \"kw=9.375; f=kw*; g=1\": column 16: expected a number, name or '(' but found ';'");
  // Too many run-time locals.
  std::string many;
  for (int i = 0; i <= kMaxLocals; ++i) many += "a" + std::to_string(i) + "=x0+" + std::to_string(i) + ";";
  const size_t column = many.find("a16=") + 1;
  expect_compile_error("a0", many, static_cast<int>(column), "too many run-time locals");
}

// ------------------------------------------------------------------ folding

TEST(Expression, ConstantExpressionsFoldToOnePush) {
  EXPECT_TRUE(single_push(comp("2*pi*3"), 2 * M_PI * 3));
  EXPECT_TRUE(single_push(comp("sin(pi/2) + E", "", {{"E", 5.0}}), 6.0));
  EXPECT_TRUE(single_push(comp("if(1 < 2, 3, 4)^2"), 9.0));
  EXPECT_TRUE(single_push(comp("0 and 1/0"), 0.0));  // the dead side is not folded
  EXPECT_TRUE(single_push(comp("1 or sqrt(-1)"), 1.0));
  EXPECT_TRUE(single_push(comp("2 and 3"), 1.0));
  // A constant condition keeps only the taken branch.
  const Program p = comp("if(1, x0, 1/0)");
  ASSERT_EQ(p.code().size(), 1u);
  EXPECT_EQ(p.code()[0].op, Op::load_var);
  // Partially constant expressions fold their constant parts.
  const Program q = comp("x0 * (2 + 3) * cos(0)");
  EXPECT_EQ(q.code().size(), 5u);  // load, push 5, mul, push 1, mul
  EXPECT_EQ(q.constants().size(), 2u);
  EXPECT_THROW(q.constant_value(), std::logic_error);
}

TEST(Expression, ConstantDomainErrorsAreCompileErrors) {
  expect_compile_error("sqrt(-1)", "", 1, "domain error");
  expect_compile_error("x0 + 1/0", "", 7, "division by zero");
  expect_compile_error("x0 + ln(0)", "", 6, "domain error");
  expect_compile_error("exp(1000)", "", 1, "non-finite result");
  expect_compile_error("(-8)^(1/3)", "", 5, "domain error");
  expect_compile_error("cot(0)", "", 1, "division by zero");
}

// ------------------------------------------------------------------ compile errors

TEST(Expression, CompileErrorsNameTheColumn) {
  {
    const ExpressionError err = compile_error("1 + * 2");
    EXPECT_EQ(err.column(), 5);
    EXPECT_EQ(std::string(err.what()),
              "in expression \"1 + * 2\": column 5: expected a number, name or '(' but found '*'");
    EXPECT_EQ(err.source(), "1 + * 2");
  }
  // Unexpected character.
  expect_compile_error("1 # 2", "", 3, "unexpected character '#'");
  expect_compile_error("x0 & y0", "", 4, "write 'and'");
  expect_compile_error("x0 || y0", "", 4, "write 'or'");
  expect_compile_error("x0 ! y0", "", 4, "unexpected character '!'");
  expect_compile_error("1e+", "", 1, "malformed number '1e+'");
  // Unbalanced parentheses.
  expect_compile_error("(1+x0", "", 6, "expected ')' to close the '(' at column 1");
  expect_compile_error("1+x0)", "", 5, "unbalanced ')'");
  expect_compile_error("sin(x0", "", 7, "expected ',' or ')' in the arguments of 'sin'");
  expect_compile_error("()", "", 2, "expected a number, name or '('");
  // Trailing input.
  expect_compile_error("1 2", "", 3, "expected an operator or the end of the expression but found '2'");
  expect_compile_error("x0 y0", "", 4, "but found 'y0'");
  expect_compile_error("x0 = 1", "", 4, "write '=='");
  // Unknown names ('e' is not a constant).
  {
    const ExpressionError err = compile_error("2*foo+1");
    EXPECT_EQ(err.column(), 3);
    const std::string m = err.what();
    EXPECT_NE(m.find("unknown name 'foo'; known variables: x0, y0, z0, x, y, z, ux, uy, uz, t, dt, dx; "
                     "constants: pi"),
              std::string::npos)
        << m;
  }
  expect_compile_error("e", "", 1, "unknown name 'e'");
  expect_compile_error("1 + SIN(x0)", "", 5, "unknown function 'SIN'");
  expect_compile_error("x0(1)", "", 3, "'x0' is not a function");
  expect_compile_error("sin + 1", "", 1, "function 'sin' needs its arguments");
  expect_compile_error("1 and", "", 6, "expected a number, name or '(' but found the end of the expression");
  // Wrong number of arguments.
  expect_compile_error("pow(1)", "", 1, "'pow' takes 2 arguments but 1 was given");
  expect_compile_error("x0 + sin(1, 2)", "", 6, "'sin' takes 1 argument but 2 were given");
  expect_compile_error("max()", "", 1, "'max' takes 2 arguments but 0 were given");
  expect_compile_error("if(x0, 1)", "", 1, "'if' takes 3 arguments but 2 were given");
  // Empty expression.
  expect_compile_error("", "", 1, "empty expression");
  expect_compile_error("   ", "", 4, "empty expression");
}

TEST(Expression, CallerMistakesAreInvalidArguments) {
  EXPECT_THROW(compile("1", VariableTable{{"x0", "x0"}}, {}), std::invalid_argument);
  EXPECT_THROW(compile("1", VariableTable{{"sin"}}, {}), std::invalid_argument);
  EXPECT_THROW(compile("1", VariableTable{{"2x"}}, {}), std::invalid_argument);
  EXPECT_THROW(compile("1", VariableTable{{"x0"}}, {{"x0", 1.0}}), std::invalid_argument);
  EXPECT_THROW(compile("1", VariableTable{{"x0"}}, {{"c", NAN}}), std::invalid_argument);
}

// The scene reader asks name_problem() before it passes a constant (issue
// 19: "bad$name" reached compile() and became an internal error).
TEST(Expression, NameProblemSaysWhyANameCannotBeAConstant) {
  EXPECT_EQ(name_problem("L0"), "");
  EXPECT_EQ(name_problem("_h_over_dp"), "");
  EXPECT_EQ(name_problem(""), "an empty name");
  EXPECT_EQ(name_problem("2x"), "a name that starts with neither a letter nor '_'");
  EXPECT_EQ(name_problem("bad$name"), "a character other than a letter, digit or '_' at column 4");
  EXPECT_EQ(name_problem("a b"), "a character other than a letter, digit or '_' at column 2");
  EXPECT_EQ(name_problem("skip"), "a reserved word (if, and, or, skip, Skip, pi)");
  EXPECT_EQ(name_problem("pi"), "a reserved word (if, and, or, skip, Skip, pi)");
  EXPECT_EQ(name_problem("sinh"), "the name of a function");
  // Whatever name_problem() accepts, compile() accepts as a constant.
  for (const char* name : {"L0", "_h_over_dp", "sinus", "iff"})
    EXPECT_NO_THROW(compile(name, VariableTable{}, {{name, 1.0}})) << name;
}

// A message lists at most 100 constants (a scene of 9,000 made one of 100 kB).
TEST(Expression, UnknownNameListsAtMost100Constants) {
  std::map<std::string, double> constants;
  for (int k = 0; k < 150; ++k) constants["c" + std::to_string(1000 + k)] = k;
  try {
    compile("foo", VariableTable{}, constants);
    FAIL() << "no error";
  } catch (const ExpressionError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("constants: pi, c1000, c1001,"), std::string::npos) << m;
    EXPECT_NE(m.find(", c1098 and 51 more"), std::string::npos) << m;  // pi and 99 of them
    EXPECT_EQ(m.find("c1099"), std::string::npos) << m;
  }
}

// ------------------------------------------------------------------ run-time errors

struct RunTimeCase {
  const char* expression;
  double x0;
  Status status;
  int column;
};

TEST(Expression, RunTimeErrorsReportStatusAndColumn) {
  const std::vector<RunTimeCase> cases = {
      {"1/(x0-0.1)", 0.1, Status::division_by_zero, 2},
      {"2 + cot(x0)", 0.0, Status::division_by_zero, 5},
      {"coth(x0)", 0.0, Status::division_by_zero, 1},
      {"pow(x0, -1)", 0.0, Status::division_by_zero, 1},
      {"sqrt(x0)", -1.0, Status::domain_error, 1},
      {"1 + ln(x0)", 0.0, Status::domain_error, 5},
      {"log(x0)", -1.0, Status::domain_error, 1},
      {"x0^0.5", -2.0, Status::domain_error, 3},
      {"pow(x0, 1.5)", -2.0, Status::domain_error, 1},
      {"asin(x0)", 1.5, Status::domain_error, 1},
      {"acos(x0)", -1.5, Status::domain_error, 1},
      {"exp(x0)", 1000.0, Status::non_finite, 1},
      {"x0*1e300", 1e10, Status::non_finite, 3},
      {"1e308 + x0", 1e308, Status::non_finite, 7},
      {"sinh(x0)", 1000.0, Status::non_finite, 1},
      {"x0 + 1", std::numeric_limits<double>::quiet_NaN(), Status::non_finite, 1},
      {"x0", std::numeric_limits<double>::infinity(), Status::non_finite, 1},
  };
  for (const RunTimeCase& c : cases) {
    const Program p = comp(c.expression);
    const Outcome<double> o = run<double>(p, {{"x0", c.x0}});
    EXPECT_EQ(o.status, c.status) << c.expression;
    ASSERT_GE(o.pc, 0) << c.expression;
    ASSERT_LT(o.pc, static_cast<int>(p.sources().size())) << c.expression;
    EXPECT_EQ(p.sources()[o.pc].column, c.column) << c.expression;
    EXPECT_EQ(o.value, -12345.0) << c.expression;  // result untouched
    std::array<double, kNumVars> vars{};
    vars[0] = c.x0;
    try {
      p.evaluate_host(vars.data());
      ADD_FAILURE() << c.expression << " did not throw";
    } catch (const ExpressionError& err) {
      EXPECT_EQ(err.column(), c.column) << c.expression;
      const std::string reason = c.status == Status::non_finite ? "non-finite" : status_text(c.status);
      EXPECT_NE(std::string(err.what()).find(reason), std::string::npos) << err.what();
    }
  }
  const Program p = comp("1/(x0-0.1)");
  const Outcome<double> o = run<double>(p, {{"x0", 0.1}});
  EXPECT_EQ(p.describe_error(o.status, o.pc), "expression \"1/(x0-0.1)\": division by zero at column 2 ('/')");
  const Program nan = comp("x0");
  const Outcome<double> n = run<double>(nan, {{"x0", NAN}});
  EXPECT_EQ(nan.describe_error(n.status, n.pc), "expression \"x0\": non-finite value of variable at column 1 ('x0')");
}

TEST(Expression, RunTimeErrorInALocalNamesTheLocalsText) {
  const Program p = comp("2*r", "r=sqrt(x0)");
  const Outcome<double> o = run<double>(p, {{"x0", -1.0}});
  EXPECT_EQ(o.status, Status::domain_error);
  EXPECT_EQ(p.describe_error(o.status, o.pc), "locals \"r=sqrt(x0)\": domain error at column 3 ('sqrt')");
}

TEST(Expression, FloatOverflowIsAnErrorInFloatOnly) {
  const Program p = comp("exp(x0)");
  EXPECT_EQ(run<double>(p, {{"x0", 100.0}}).status, Status::ok);
  const Outcome<float> f = run<float>(p, {{"x0", 100.0}});
  EXPECT_EQ(f.status, Status::non_finite);
  EXPECT_EQ(f.pc, 1);
  // A constant beyond float range cannot be used in single precision.
  const Program big = comp("x0 + 1e39");
  EXPECT_EQ(run<double>(big, {{"x0", 1.0}}).value, 1e39 + 1.0);
  try {
    big.host_view<float>();
    ADD_FAILURE() << "expected an error";
  } catch (const ExpressionError& err) {
    EXPECT_EQ(err.column(), 6);
  }
}

TEST(Expression, StackDepthIsCheckedAtCompileTime) {
  // x0+(x0+(...)) needs one stack entry per nesting level.
  auto nested = [](int n) {
    std::string e;
    for (int i = 1; i < n; ++i) e += "x0+(";
    e += "x0";
    return e + std::string(n - 1, ')');
  };
  const Program fits = comp(nested(kMaxStack));
  EXPECT_EQ(fits.max_stack(), kMaxStack);
  EXPECT_EQ(run<double>(fits, {{"x0", 1.0}}).value, kMaxStack);
  EXPECT_EQ(run<float>(fits, {{"x0", 1.0}}).value, kMaxStack);
  const std::string deep = nested(kMaxStack + 1);
  const int last_x0 = static_cast<int>(deep.rfind("x0")) + 1;
  expect_compile_error(deep, "", last_x0, "expression too deeply nested");
  // Constant nesting folds, but the parser's own depth is bounded too.
  EXPECT_TRUE(single_push(comp(std::string(150, '(') + "1" + std::string(150, ')')), 1.0));
  expect_compile_error(std::string(300, '(') + "1" + std::string(300, ')'), "", 201, "too deeply nested");
}

TEST(Expression, EmptyProgramIsBad) {
  const Program empty;
  double r = 0;
  int pc = -1;
  EXPECT_EQ(evaluate<double>(empty.host_view<double>(), nullptr, &r, &pc), Status::bad_program);
}

// ------------------------------------------------------------------ the seed's cantilever (Fig. 8, eq. 67-68)

TEST(Expression, SeedCantileverInitialVelocity) {
  const std::string locals = "L0=0.2; kw=9.375; cs=57.0";
  const std::string expression =
      "if(x0<=0.0,0.0,if(t<=0.0,0.01 * cs * ((cos(kw*L0)+cosh(kw*L0))*(cosh(kw*x0)-cos(kw*x0)) + "
      "(sin(kw*L0)-sinh(kw*L0))*(sinh(kw*x0)-sin(kw*x0)))/ ((cos(kw*L0)+cosh(kw*L0))*(cosh(kw*L0)-cos(kw*L0)) + "
      "(sin(kw*L0)-sinh(kw*L0))*(sinh(kw*L0)-sin(kw*L0))),skip))";
  const Program p = comp(expression, locals);
  EXPECT_TRUE(p.may_skip());

  const double L0 = 0.2, kw = 9.375, cs = 57.0;
  auto f = [&](double x) {  // eq. 68
    return (std::cos(kw * L0) + std::cosh(kw * L0)) * (std::cosh(kw * x) - std::cos(kw * x)) +
           (std::sin(kw * L0) - std::sinh(kw * L0)) * (std::sinh(kw * x) - std::sin(kw * x));
  };
  for (double x0 : {-0.05, 0.0, 0.01, 0.05, 0.1, 0.15, 0.2}) {
    for (double t : {-1.0, 0.0, 1e-6, 0.5}) {
      const std::vector<std::pair<std::string, double>> v{{"x0", x0}, {"t", t}};
      const Outcome<double> d = run<double>(p, v);
      const Outcome<float> s = run<float>(p, v);
      if (x0 <= 0.0) {  // eq. 67, first case
        EXPECT_EQ(d.status, Status::ok);
        EXPECT_EQ(d.value, 0.0);
        EXPECT_EQ(s.value, 0.0f);
      } else if (t <= 0.0) {
        const double expected = 0.01 * cs * f(x0) / f(L0);
        EXPECT_EQ(d.status, Status::ok);
        EXPECT_NEAR(d.value, expected, 1e-13 * std::fabs(expected)) << x0;
        EXPECT_EQ(s.status, Status::ok);
        EXPECT_NEAR(s.value, expected, 1e-5 * std::fabs(expected)) << x0;
      } else {
        EXPECT_EQ(d.status, Status::skipped);
        EXPECT_EQ(s.status, Status::skipped);
      }
    }
  }
  // At the free end the profile equals its normalisation: 0.01 cs.
  EXPECT_NEAR(run<double>(p, {{"x0", L0}, {"t", 0.0}}).value, 0.01 * cs, 1e-12);
  // The seed's second expression (Fig. 8, id 2).
  const Program clamp = comp("if(x0<0.0,0.0,skip)");
  EXPECT_EQ(run<double>(clamp, {{"x0", -0.1}}).value, 0.0);
  EXPECT_EQ(run<double>(clamp, {{"x0", 0.1}}).status, Status::skipped);
}

// ------------------------------------------------------------------ float and double

TEST(Expression, FloatAgreesWithDouble) {
  struct Case {
    const char* expression;
    std::function<double(double, double, double)> reference;  // of x0, y0, t
  };
  const std::vector<Case> cases = {
      {"sqrt(x0*x0 + y0*y0)", [](double x, double y, double) { return std::sqrt(x * x + y * y); }},
      {"sin(2*pi*t)*exp(-x0)", [](double x, double, double t) { return std::sin(2 * M_PI * t) * std::exp(-x); }},
      {"if(x0 > y0, pow(x0, 1.5), ln(1 + y0^2))",
       [](double x, double y, double) { return x > y ? std::pow(x, 1.5) : std::log(1 + y * y); }},
      {"tanh(x0/0.3) + atan2(y0, x0) - abs(t - 1)",
       [](double x, double y, double t) { return std::tanh(x / 0.3) + std::atan2(y, x) - std::fabs(t - 1); }},
      {"f*g", [](double x, double y, double t) { return (x + 2 * t) * std::cosh(y); }},
  };
  for (const Case& c : cases) {
    const Program p = comp(c.expression, "f = x0 + 2*t; g = cosh(y0)");
    for (double x : {0.3, 1.7})
      for (double y : {0.2, 2.5})
        for (double t : {0.1, 0.35}) {
          const std::vector<std::pair<std::string, double>> v{{"x0", x}, {"y0", y}, {"t", t}};
          const double expected = c.reference(x, y, t);
          const Outcome<double> d = run<double>(p, v);
          const Outcome<float> s = run<float>(p, v);
          ASSERT_EQ(d.status, Status::ok) << c.expression;
          ASSERT_EQ(s.status, Status::ok) << c.expression;
          EXPECT_NEAR(d.value, expected, 1e-13 * std::fabs(expected)) << c.expression;
          EXPECT_NEAR(s.value, expected, 1e-5 * std::fabs(expected)) << c.expression;
        }
  }
}

}  // namespace
}  // namespace mfsd::expr
