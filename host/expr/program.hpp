// A compiled user expression (seed 001 section 3.4): bytecode, constant table
// in double and float, and per-instruction source positions for messages.
// compile() builds it once on the host; host_view() (or device copies of
// code() and constants_as<Real>()) feed kernels/expr/interpreter.hpp.
//
//   VariableTable vars{{"x0", "y0", "z0", "t"}};
//   Program p = compile("if(x0<=0, 0, skip)", vars, {});
//   Status s = evaluate(p.host_view<double>(), values, &out, &pc);
//   if (s > Status::skipped) throw std::runtime_error(p.describe_error(s, pc));
#pragma once
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "host/expr/expression_error.hpp"
#include "kernels/expr/bytecode.hpp"

namespace mfsd::expr {

// The variables an expression may read; a variable's slot is its position
// in `names` (the index into the `vars` array passed to evaluate()).
struct VariableTable {
  std::vector<std::string> names;
  int slot(const std::string& name) const;  // -1 when unknown
};

// Where one instruction came from, for run-time error messages.
struct InstrSource {
  int column = 0;          // 1-based column in the expression or the locals text
  bool in_locals = false;  // true: `column` refers to the locals text
  std::string token;       // operator, function, name or number, e.g. "/", "sqrt", "x0"
};

class Program;

// Compiles `expression`, reading the variables of `vars`, the named constants
// `constants` (folded at compile time) and the optional `locals`
// ("L0=0.2; kw=9.375; f=kw*x0"). Throws ExpressionError on any compile error
// and std::invalid_argument on an inconsistent `vars`/`constants` (a caller bug).
Program compile(const std::string& expression, const VariableTable& vars,
                const std::map<std::string, double>& constants, const std::string& locals = "");

// Why `name` cannot name a constant (or variable) of compile(): not an
// identifier, a reserved word or a function; empty when it can.
std::string name_problem(const std::string& name);

// Short human names ("division by zero", "push_const", "sqrt").
const char* status_text(Status status);
const char* op_name(Op op);
const char* func_name(Func func);  // the language's spelling ("log" for Func::log10)

class Program {
 public:
  Program() = default;  // empty: evaluates to Status::bad_program

  const std::string& expression() const { return expression_; }
  const std::string& locals() const { return locals_; }
  const std::vector<Instr>& code() const { return code_; }
  const std::vector<InstrSource>& sources() const { return sources_; }  // one per instruction
  const std::vector<double>& constants() const { return constants_; }
  template <class Real>
  const std::vector<Real>& constants_as() const;
  int max_stack() const { return max_stack_; }  // deepest stack the program reaches
  int n_locals() const { return n_locals_; }    // run-time local slots defined

  // True when the whole expression folded to one number (no variable, no skip).
  bool is_constant() const;
  double constant_value() const;  // throws std::logic_error unless is_constant()
  bool may_skip() const { return may_skip_; }

  // View of the host-side arrays. For float, throws ExpressionError if a
  // constant overflows single precision.
  template <class Real>
  ProgramView<Real> host_view() const {
    static_assert(std::is_same_v<Real, float> || std::is_same_v<Real, double>, "Real must be float or double");
    if constexpr (std::is_same_v<Real, float>) require_float_constants();
    const std::vector<Real>& c = constants_as<Real>();
    return ProgramView<Real>{code_.data(), static_cast<int>(code_.size()), c.data(), static_cast<int>(c.size())};
  }

  // E.g.  expression "1/(x0-0.1)": division by zero at column 2 ('/')
  // `pc` is the instruction index evaluate() reported.
  std::string describe_error(Status status, int pc) const;

  // Evaluates in double on the host; throws ExpressionError (message from
  // describe_error) on a run-time error and also when the result is 'skip'.
  double evaluate_host(const double* vars) const;

  // One instruction per line, for debugging and tests.
  std::string disassemble() const;

 private:
  friend Program compile(const std::string&, const VariableTable&, const std::map<std::string, double>&,
                         const std::string&);
  Program(std::string expression, std::string locals, std::vector<Instr> code, std::vector<InstrSource> sources,
          std::vector<double> constants, int max_stack, int n_locals);
  void require_float_constants() const;

  std::string expression_;
  std::string locals_;
  std::vector<Instr> code_;
  std::vector<InstrSource> sources_;
  std::vector<double> constants_;
  std::vector<float> constants_float_;
  int float_overflow_ = -1;  // index of the first constant beyond float range, or -1
  int max_stack_ = 0;
  int n_locals_ = 0;
  bool may_skip_ = false;
};

template <>
inline const std::vector<double>& Program::constants_as<double>() const {
  return constants_;
}
template <>
inline const std::vector<float>& Program::constants_as<float>() const {
  return constants_float_;
}

}  // namespace mfsd::expr
