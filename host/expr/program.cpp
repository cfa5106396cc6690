#include "host/expr/program.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "kernels/expr/interpreter.hpp"

namespace mfsd::expr {

int VariableTable::slot(const std::string& name) const {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

const char* status_text(Status status) {
  switch (status) {
    case Status::ok:
      return "no error";
    case Status::skipped:
      return "skipped";
    case Status::division_by_zero:
      return "division by zero";
    case Status::domain_error:
      return "domain error";
    case Status::non_finite:
      return "non-finite result";
    case Status::bad_program:
      return "invalid program";
  }
  return "unknown status";
}

const char* op_name(Op op) {
  switch (op) {
    case Op::push_const:
      return "push_const";
    case Op::load_var:
      return "load_var";
    case Op::load_local:
      return "load_local";
    case Op::store_local:
      return "store_local";
    case Op::neg:
      return "neg";
    case Op::add:
      return "add";
    case Op::sub:
      return "sub";
    case Op::mul:
      return "mul";
    case Op::div:
      return "div";
    case Op::lt:
      return "lt";
    case Op::gt:
      return "gt";
    case Op::le:
      return "le";
    case Op::ge:
      return "ge";
    case Op::eq:
      return "eq";
    case Op::ne:
      return "ne";
    case Op::call1:
      return "call1";
    case Op::call2:
      return "call2";
    case Op::to_bool:
      return "to_bool";
    case Op::and_jump:
      return "and_jump";
    case Op::or_jump:
      return "or_jump";
    case Op::jump:
      return "jump";
    case Op::jump_if_false:
      return "jump_if_false";
    case Op::skip:
      return "skip";
  }
  return "?";
}

const char* func_name(Func func) {
  switch (func) {
    case Func::sin:
      return "sin";
    case Func::cos:
      return "cos";
    case Func::tan:
      return "tan";
    case Func::cot:
      return "cot";
    case Func::sinh:
      return "sinh";
    case Func::cosh:
      return "cosh";
    case Func::tanh:
      return "tanh";
    case Func::coth:
      return "coth";
    case Func::exp:
      return "exp";
    case Func::sqrt:
      return "sqrt";
    case Func::abs:
      return "abs";
    case Func::log10:
      return "log";
    case Func::ln:
      return "ln";
    case Func::asin:
      return "asin";
    case Func::acos:
      return "acos";
    case Func::atan:
      return "atan";
    case Func::floor:
      return "floor";
    case Func::ceil:
      return "ceil";
    case Func::pow:
      return "pow";
    case Func::min:
      return "min";
    case Func::max:
      return "max";
    case Func::atan2:
      return "atan2";
  }
  return "?";
}

Program::Program(std::string expression, std::string locals, std::vector<Instr> code, std::vector<InstrSource> sources,
                 std::vector<double> constants, int max_stack, int n_locals)
    : expression_(std::move(expression)),
      locals_(std::move(locals)),
      code_(std::move(code)),
      sources_(std::move(sources)),
      constants_(std::move(constants)),
      max_stack_(max_stack),
      n_locals_(n_locals) {
  constants_float_.reserve(constants_.size());
  for (size_t i = 0; i < constants_.size(); ++i) {
    const double v = constants_[i];
    if (float_overflow_ < 0 && std::fabs(v) > static_cast<double>(std::numeric_limits<float>::max()))
      float_overflow_ = static_cast<int>(i);
    constants_float_.push_back(static_cast<float>(v));
  }
  for (const Instr& in : code_)
    if (in.op == Op::skip) may_skip_ = true;
}

bool Program::is_constant() const { return code_.size() == 1 && code_[0].op == Op::push_const; }

double Program::constant_value() const {
  if (!is_constant()) throw std::logic_error("expression \"" + expression_ + "\" is not a constant");
  return constants_[code_[0].arg];
}

void Program::require_float_constants() const {
  if (float_overflow_ < 0) return;
  int column = 0;
  bool in_locals = false;
  for (size_t pc = 0; pc < code_.size(); ++pc)
    if (code_[pc].op == Op::push_const && code_[pc].arg == float_overflow_) {
      column = sources_[pc].column;
      in_locals = sources_[pc].in_locals;
      break;
    }
  std::ostringstream value;
  value << constants_[float_overflow_];
  throw ExpressionError::compile_error(in_locals ? "locals" : "expression", in_locals ? locals_ : expression_, column,
                                       "the constant " + value.str() + " does not fit in single precision");
}

std::string Program::describe_error(Status status, int pc) const {
  const bool known = pc >= 0 && pc < static_cast<int>(sources_.size());
  const bool in_locals = known && sources_[pc].in_locals;
  std::string m =
      std::string(in_locals ? "locals" : "expression") + " \"" + (in_locals ? locals_ : expression_) + "\": ";
  if (status == Status::non_finite && known && code_[pc].op == Op::load_var)
    m += "non-finite value of variable";
  else
    m += status_text(status);
  if (known) m += " at column " + std::to_string(sources_[pc].column) + " ('" + sources_[pc].token + "')";
  return m;
}

double Program::evaluate_host(const double* vars) const {
  double result = 0.0;
  int pc = -1;
  const Status s = evaluate(host_view<double>(), vars, &result, &pc);
  if (s == Status::ok) return result;
  if (s == Status::skipped)
    throw ExpressionError("expression \"" + expression_ + "\": evaluated to 'skip' where a value is needed",
                          expression_, 0, "evaluated to 'skip' where a value is needed");
  const bool known = pc >= 0 && pc < static_cast<int>(sources_.size());
  throw ExpressionError(describe_error(s, pc), known && sources_[pc].in_locals ? locals_ : expression_,
                        known ? sources_[pc].column : 0, status_text(s));
}

std::string Program::disassemble() const {
  std::ostringstream s;
  for (size_t pc = 0; pc < code_.size(); ++pc) {
    const Instr& in = code_[pc];
    s << pc << ": " << op_name(in.op);
    switch (in.op) {
      case Op::push_const:
        s << ' ' << constants_[in.arg];
        break;
      case Op::call1:
      case Op::call2:
        s << ' ' << func_name(static_cast<Func>(in.arg));
        break;
      case Op::load_var:
      case Op::load_local:
      case Op::store_local:
      case Op::and_jump:
      case Op::or_jump:
      case Op::jump:
      case Op::jump_if_false:
        s << ' ' << in.arg;
        break;
      default:
        break;
    }
    if (pc < sources_.size())
      s << "    ; " << (sources_[pc].in_locals ? "locals " : "") << "column " << sources_[pc].column << " '"
        << sources_[pc].token << "'";
    s << '\n';
  }
  return s.str();
}

}  // namespace mfsd::expr
