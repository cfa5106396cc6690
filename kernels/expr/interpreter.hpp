// Stack-machine interpreter of the expression bytecode (kernels/expr/bytecode.hpp).
// One source for CPU threads and CUDA: no recursion, no allocation, fixed-size
// stack and locals. Run-time errors are not turned into NaN: evaluation stops
// at the first one and reports its status and instruction index, which the
// host Program maps back to a source column.
//
// The apply_* functions hold the semantics of every operator and function;
// the compiler's constant folding calls them too (with Real = double), so a
// folded value and an interpreted one follow the same rules.
#pragma once
#include "kernels/core/math.hpp"
#include "kernels/expr/bytecode.hpp"

namespace mfsd::expr {

namespace detail {
template <class Real>
MFSD_HD MFSD_FORCEINLINE Status finite_result(Real r, Real* out) {
  if (!math::isfinite(r)) return Status::non_finite;
  *out = r;
  return Status::ok;
}
}  // namespace detail

// Arithmetic (add, sub, mul, div) and comparison (lt ... ne) operators.
template <class Real>
MFSD_HD MFSD_FORCEINLINE Status apply_binary(Op op, Real a, Real b, Real* out) {
  const Real one(1), zero(0);
  switch (op) {
    case Op::add:
      return detail::finite_result(a + b, out);
    case Op::sub:
      return detail::finite_result(a - b, out);
    case Op::mul:
      return detail::finite_result(a * b, out);
    case Op::div:
      if (b == zero) return Status::division_by_zero;
      return detail::finite_result(a / b, out);
    case Op::lt:
      *out = a < b ? one : zero;
      return Status::ok;
    case Op::gt:
      *out = a > b ? one : zero;
      return Status::ok;
    case Op::le:
      *out = a <= b ? one : zero;
      return Status::ok;
    case Op::ge:
      *out = a >= b ? one : zero;
      return Status::ok;
    case Op::eq:
      *out = a == b ? one : zero;
      return Status::ok;
    case Op::ne:
      *out = a != b ? one : zero;
      return Status::ok;
    default:
      return Status::bad_program;
  }
}

// One-argument functions.
template <class Real>
MFSD_HD MFSD_FORCEINLINE Status apply_call1(Func f, Real x, Real* out) {
  const Real one(1), zero(0);
  switch (f) {
    case Func::sin:
      return detail::finite_result(math::sin(x), out);
    case Func::cos:
      return detail::finite_result(math::cos(x), out);
    case Func::tan:
      return detail::finite_result(math::tan(x), out);
    case Func::cot: {
      const Real s = math::sin(x);
      if (s == zero) return Status::division_by_zero;
      return detail::finite_result(math::cos(x) / s, out);
    }
    case Func::sinh:
      return detail::finite_result(math::sinh(x), out);
    case Func::cosh:
      return detail::finite_result(math::cosh(x), out);
    case Func::tanh:
      return detail::finite_result(math::tanh(x), out);
    case Func::coth: {
      const Real t = math::tanh(x);  // 1/tanh stays finite where cosh/sinh would overflow
      if (t == zero) return Status::division_by_zero;
      return detail::finite_result(one / t, out);
    }
    case Func::exp:
      return detail::finite_result(math::exp(x), out);
    case Func::sqrt:
      if (x < zero) return Status::domain_error;
      return detail::finite_result(math::sqrt(x), out);
    case Func::abs:
      return detail::finite_result(math::fabs(x), out);
    case Func::log10:
      if (x <= zero) return Status::domain_error;
      return detail::finite_result(math::log10(x), out);
    case Func::ln:
      if (x <= zero) return Status::domain_error;
      return detail::finite_result(math::log(x), out);
    case Func::asin:
      if (x < -one || x > one) return Status::domain_error;
      return detail::finite_result(math::asin(x), out);
    case Func::acos:
      if (x < -one || x > one) return Status::domain_error;
      return detail::finite_result(math::acos(x), out);
    case Func::atan:
      return detail::finite_result(math::atan(x), out);
    case Func::floor:
      return detail::finite_result(math::floor(x), out);
    case Func::ceil:
      return detail::finite_result(math::ceil(x), out);
    default:
      return Status::bad_program;
  }
}

// Two-argument functions (pow is also the operator '^').
template <class Real>
MFSD_HD MFSD_FORCEINLINE Status apply_call2(Func f, Real a, Real b, Real* out) {
  const Real zero(0);
  switch (f) {
    case Func::pow:
      if (a < zero && b != math::floor(b)) return Status::domain_error;  // no real root
      if (a == zero && b < zero) return Status::division_by_zero;        // 0^-n = 1/0^n
      return detail::finite_result(math::pow(a, b), out);
    case Func::min:
      *out = math::min(a, b);
      return Status::ok;
    case Func::max:
      *out = math::max(a, b);
      return Status::ok;
    case Func::atan2:
      return detail::finite_result(math::atan2(a, b), out);
    default:
      return Status::bad_program;
  }
}

// Evaluates program `p` with variable values `vars` (indexed by slot).
// Returns Status::ok and writes *result; Status::skipped when a 'skip'
// branch was taken (*result untouched); otherwise an error status, with the
// failing instruction index in *error_pc (if error_pc is not null).
// `p` must come from the host compiler, which guarantees stack balance and
// bounds; only the stack capacity and the final depth are re-checked here.
template <class Real>
MFSD_HD Status evaluate(const ProgramView<Real>& p, const Real* vars, Real* result, int* error_pc) {
  // The top of the stack lives in `top`; stack[0] holds a dummy below the
  // first value, so a balanced program ends with sp == 1.
  Real stack[kMaxStack];
  Real locals[kMaxLocals];
  Real top = Real(0);
  int sp = 0;
  const Instr* const code = p.code;
  const int n = p.n_code;
  int pc = 0;
  Status st = Status::ok;

#define MFSD_EXPR_FAIL(status)    \
  do {                            \
    if (error_pc) *error_pc = pc; \
    return (status);              \
  } while (0)
#define MFSD_EXPR_PUSH(value)                                 \
  do {                                                        \
    if (sp >= kMaxStack) MFSD_EXPR_FAIL(Status::bad_program); \
    stack[sp++] = top;                                        \
    top = (value);                                            \
  } while (0)
#define MFSD_EXPR_BINARY(name)                 \
  case Op::name: {                             \
    const Real b = top;                        \
    top = stack[--sp];                         \
    st = apply_binary(Op::name, top, b, &top); \
    if (st != Status::ok) MFSD_EXPR_FAIL(st);  \
    break;                                     \
  }

  while (pc < n) {
    const Instr in = code[pc];
    switch (in.op) {
      case Op::push_const:
        MFSD_EXPR_PUSH(p.consts[in.arg]);
        break;
      case Op::load_var: {
        const Real v = vars[in.arg];
        if (!math::isfinite(v)) MFSD_EXPR_FAIL(Status::non_finite);
        MFSD_EXPR_PUSH(v);
        break;
      }
      case Op::load_local:
        MFSD_EXPR_PUSH(locals[in.arg]);
        break;
      case Op::store_local:
        locals[in.arg] = top;
        top = stack[--sp];
        break;
      case Op::neg:
        top = -top;
        break;
        MFSD_EXPR_BINARY(add)
        MFSD_EXPR_BINARY(sub)
        MFSD_EXPR_BINARY(mul)
        MFSD_EXPR_BINARY(div)
        MFSD_EXPR_BINARY(lt)
        MFSD_EXPR_BINARY(gt)
        MFSD_EXPR_BINARY(le)
        MFSD_EXPR_BINARY(ge)
        MFSD_EXPR_BINARY(eq)
        MFSD_EXPR_BINARY(ne)
      case Op::call1:
        st = apply_call1(static_cast<Func>(in.arg), top, &top);
        if (st != Status::ok) MFSD_EXPR_FAIL(st);
        break;
      case Op::call2: {
        const Real b = top;
        top = stack[--sp];
        st = apply_call2(static_cast<Func>(in.arg), top, b, &top);
        if (st != Status::ok) MFSD_EXPR_FAIL(st);
        break;
      }
      case Op::to_bool:
        top = top != Real(0) ? Real(1) : Real(0);
        break;
      case Op::and_jump:
        if (top == Real(0)) {
          top = Real(0);
          pc = in.arg;
          continue;
        }
        top = stack[--sp];
        break;
      case Op::or_jump:
        if (top != Real(0)) {
          top = Real(1);
          pc = in.arg;
          continue;
        }
        top = stack[--sp];
        break;
      case Op::jump:
        pc = in.arg;
        continue;
      case Op::jump_if_false: {
        const bool taken = top == Real(0);
        top = stack[--sp];
        if (taken) {
          pc = in.arg;
          continue;
        }
        break;
      }
      case Op::skip:
        return Status::skipped;
      default:
        MFSD_EXPR_FAIL(Status::bad_program);
    }
    ++pc;
  }
#undef MFSD_EXPR_BINARY
#undef MFSD_EXPR_PUSH
#undef MFSD_EXPR_FAIL

  if (sp != 1) {
    if (error_pc) *error_pc = n > 0 ? n - 1 : 0;
    return Status::bad_program;
  }
  *result = top;
  return Status::ok;
}

}  // namespace mfsd::expr
