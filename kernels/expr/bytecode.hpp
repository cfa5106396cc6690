// Bytecode of the user expression language (seed 001 section 3.4, Tables 1-3).
// host/expr/compiler.cpp compiles an expression once into this form;
// kernels/expr/interpreter.hpp evaluates it per particle on host or device.
//
// The machine is a stack machine. Each instruction is 4 bytes: an opcode and
// one 16-bit argument (constant index, variable slot, local slot, absolute
// jump target or function id, depending on the opcode).
#pragma once
#include <cstdint>

#include "kernels/core/config.hpp"

namespace mfsd::expr {

// Fixed capacities of the interpreter; the compiler rejects programs that
// would exceed them.
inline constexpr int kMaxStack = 32;
inline constexpr int kMaxLocals = 16;

enum class Op : std::uint8_t {
  push_const,   // push consts[arg]
  load_var,     // push vars[arg]; a non-finite variable is an error
  load_local,   // push locals[arg]
  store_local,  // locals[arg] = pop
  neg,          // top = -top
  add,          // b = pop, a = pop, push a op b (likewise for sub ... ne)
  sub,
  mul,
  div,  // b == 0 is a division by zero
  lt,   // comparisons push 1 or 0
  gt,
  le,
  ge,
  eq,
  ne,
  call1,          // top = f(top), f = Func(arg)
  call2,          // b = pop, a = pop, push f(a, b), f = Func(arg)
  to_bool,        // top = (top != 0)
  and_jump,       // if top == 0: top = 0, goto arg; else pop   (short-circuit 'and')
  or_jump,        // if top != 0: top = 1, goto arg; else pop   (short-circuit 'or')
  jump,           // goto arg
  jump_if_false,  // c = pop; if c == 0: goto arg
  skip,           // stop: the result is "leave the target untouched"
};

// Functions called by call1 (one argument) and call2 (two arguments).
enum class Func : std::int16_t {
  // one argument
  sin,
  cos,
  tan,
  cot,
  sinh,
  cosh,
  tanh,
  coth,
  exp,
  sqrt,
  abs,
  log10,  // the language's 'log'
  ln,
  asin,
  acos,
  atan,
  floor,
  ceil,
  // two arguments
  pow,  // also the operator '^'
  min,
  max,
  atan2,
};

struct Instr {
  Op op;
  std::uint8_t pad;
  std::int16_t arg;
};
static_assert(sizeof(Instr) == 4, "Instr must stay 4 bytes");

// Outcome of one evaluation. Every status after `skipped` is an error.
enum class Status : int { ok = 0, skipped, division_by_zero, domain_error, non_finite, bad_program };

// Raw view of a compiled program: plain old data, copied by value into a
// kernel functor. The pointers refer to host or device memory, matching where
// the evaluation runs.
template <class Real>
struct ProgramView {
  const Instr* code;
  int n_code;
  const Real* consts;
  int n_consts;
};

}  // namespace mfsd::expr
