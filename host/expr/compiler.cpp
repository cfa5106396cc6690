// Compiler of the user expression language (seed 001 section 3.4, Tables 1-3):
// tokenizer -> recursive-descent parser (AST) -> skip check -> constant
// folding -> code generation for kernels/expr/interpreter.hpp.
//
// Grammar (precedence low to high; Table 3 of seed 001):
//   expression := or
//   or         := and { 'or' and }                        left-assoc.
//   and        := comparison { 'and' comparison }         left-assoc.
//   comparison := sum { ('<'|'>'|'<='|'>='|'=='|'!=') sum }  left-assoc.
//   sum        := product { ('+'|'-') product }           left-assoc.
//   product    := unary { ('*'|'/') unary }               left-assoc.
//   unary      := ('-'|'+') unary | power                 -x^2 = -(x^2)
//   power      := primary [ '^' unary ]                   right-assoc.; 2^-1 parses
//   primary    := number | name | 'pi' | 'skip' | 'Skip'
//               | name '(' expression { ',' expression } ')'    (functions, 'if')
//               | '(' expression ')'
//   number     := digits [ '.' digits ] | '.' digits, then optional [eE][+-]digits
//   locals     := [ definition { ';' definition } [ ';' ] ]
//   definition := name '=' expression
//
// Semantics fixed here: comparisons give 1 or 0; 'and'/'or' short-circuit and
// give 1 or 0; if(c, a, b) evaluates only the taken branch; 'skip' may only be
// a branch of an 'if' whose value is the result of the whole expression.
// Locals are evaluated in order before the expression (run-time ones only if
// the expression uses them); locals of constants fold to constants.
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "host/expr/program.hpp"
#include "kernels/expr/interpreter.hpp"

namespace mfsd::expr {
namespace {

constexpr int kMaxParseDepth = 200;  // bounds host recursion; far beyond kMaxStack anyway
constexpr int kMaxIndex = 32767;     // Instr::arg is int16

struct FunctionInfo {
  const char* name;
  Func func;
  int arity;
};

constexpr FunctionInfo kFunctions[] = {
    {"sin", Func::sin, 1},     {"cos", Func::cos, 1},     {"tan", Func::tan, 1},   {"cot", Func::cot, 1},
    {"sinh", Func::sinh, 1},   {"cosh", Func::cosh, 1},   {"tanh", Func::tanh, 1}, {"coth", Func::coth, 1},
    {"exp", Func::exp, 1},     {"sqrt", Func::sqrt, 1},   {"abs", Func::abs, 1},   {"log", Func::log10, 1},
    {"ln", Func::ln, 1},       {"asin", Func::asin, 1},   {"acos", Func::acos, 1}, {"atan", Func::atan, 1},
    {"floor", Func::floor, 1}, {"ceil", Func::ceil, 1},   {"pow", Func::pow, 2},   {"min", Func::min, 2},
    {"max", Func::max, 2},     {"atan2", Func::atan2, 2},
};

const FunctionInfo* find_function(const std::string& name) {
  for (const FunctionInfo& f : kFunctions)
    if (name == f.name) return &f;
  return nullptr;
}

bool is_reserved(const std::string& name) {
  return name == "if" || name == "and" || name == "or" || name == "skip" || name == "Skip" || name == "pi";
}

bool is_name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// At most 100 names: a message listing thousands of constants helps nobody.
std::string join(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  constexpr size_t kMaxListed = 100;
  std::string s;
  for (size_t k = 0; k < names.size() && k < kMaxListed; ++k) s += (s.empty() ? "" : ", ") + names[k];
  if (names.size() > kMaxListed) s += " and " + std::to_string(names.size() - kMaxListed) + " more";
  return s;
}

// The text being compiled (the expression or the locals) and how to report in it.
struct Source {
  const char* kind;  // "expression" or "locals"
  const std::string& text;
  bool in_locals;

  [[noreturn]] void fail(int column, const std::string& reason) const {
    throw ExpressionError::compile_error(kind, text, column, reason);
  }
};

// ---------------------------------------------------------------- tokens

enum class Tok { number, name, op, lparen, rparen, comma, semicolon, assign, end };

struct Token {
  Tok kind;
  std::string text;
  int column;  // 1-based
  double value = 0.0;
};

std::string describe(const Token& t, const Source& src) {
  if (t.kind == Tok::end) return std::string("the end of the ") + src.kind;
  return "'" + t.text + "'";
}

int scan_number(const Source& src, size_t start, double* value) {
  const std::string& s = src.text;
  size_t i = start;
  while (i < s.size() && is_digit(s[i])) ++i;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && is_digit(s[i])) ++i;
  }
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    size_t j = i + 1;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
    if (j >= s.size() || !is_digit(s[j]))
      src.fail(static_cast<int>(start) + 1,
               "malformed number '" + s.substr(start, j - start) + "': the exponent needs digits");
    while (j < s.size() && is_digit(s[j])) ++j;
    i = j;
  }
  const auto r = std::from_chars(s.data() + start, s.data() + i, *value);
  if (r.ec != std::errc() || r.ptr != s.data() + i)
    src.fail(static_cast<int>(start) + 1, "number '" + s.substr(start, i - start) + "' is out of range");
  return static_cast<int>(i - start);
}

std::vector<Token> tokenize(const Source& src) {
  const std::string& s = src.text;
  std::vector<Token> tokens;
  size_t i = 0;
  while (i < s.size()) {
    const char c = s[i];
    const int column = static_cast<int>(i) + 1;
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      ++i;
    } else if (is_digit(c) || (c == '.' && i + 1 < s.size() && is_digit(s[i + 1]))) {
      Token t{Tok::number, "", column};
      const int len = scan_number(src, i, &t.value);
      t.text = s.substr(i, len);
      tokens.push_back(t);
      i += len;
    } else if (is_name_start(c)) {
      size_t j = i;
      while (j < s.size() && is_name_char(s[j])) ++j;
      tokens.push_back(Token{Tok::name, s.substr(i, j - i), column});
      i = j;
    } else {
      const std::string two = s.substr(i, 2);
      if (two == "<=" || two == ">=" || two == "==" || two == "!=") {
        tokens.push_back(Token{Tok::op, two, column});
        i += 2;
        continue;
      }
      Tok kind;
      switch (c) {
        case '<':
        case '>':
        case '+':
        case '-':
        case '*':
        case '/':
        case '^':
          kind = Tok::op;
          break;
        case '(':
          kind = Tok::lparen;
          break;
        case ')':
          kind = Tok::rparen;
          break;
        case ',':
          kind = Tok::comma;
          break;
        case ';':
          kind = Tok::semicolon;
          break;
        case '=':
          kind = Tok::assign;
          break;
        case '&':
          src.fail(column, "unexpected character '&' (write 'and')");
        case '|':
          src.fail(column, "unexpected character '|' (write 'or')");
        default: {
          const bool printable = std::isprint(static_cast<unsigned char>(c));
          char hex[8];
          std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          src.fail(column, "unexpected character '" + (printable ? std::string(1, c) : std::string(hex)) + "'");
        }
      }
      tokens.push_back(Token{kind, std::string(1, c), column});
      ++i;
    }
  }
  tokens.push_back(Token{Tok::end, "", static_cast<int>(s.size()) + 1});
  return tokens;
}

// ---------------------------------------------------------------- AST

struct Node {
  enum class Kind { number, variable, local, skip, negate, binary, logical_and, logical_or, call, if_then_else };
  Kind kind;
  int column;
  std::string token;
  double value = 0.0;     // number
  int slot = 0;           // variable, local
  Op op = Op::add;        // binary
  Func func = Func::sin;  // call
  std::vector<std::unique_ptr<Node>> kids;
};
using NodePtr = std::unique_ptr<Node>;

NodePtr make_node(Node::Kind kind, const Token& t) {
  NodePtr n(new Node{kind, t.column, t.text, 0.0, 0, Op::add, Func::sin, {}});
  return n;
}

// Names visible to an expression: caller's variables and constants, 'pi',
// and the locals defined so far.
struct Scope {
  const VariableTable& vars;
  const std::map<std::string, double>& constants;
  std::map<std::string, double> constant_locals;
  std::map<std::string, int> runtime_locals;  // name -> slot
  std::map<std::string, int> local_columns;   // name -> column of its definition
  std::vector<std::string> local_names;       // in definition order
  std::vector<int> runtime_local_columns;     // by slot

  std::string known_names() const {
    std::vector<std::string> consts{"pi"};
    for (const auto& kv : constants) consts.push_back(kv.first);
    std::string s = "known variables: " + join(vars.names) + "; constants: " + join(consts);
    if (!local_names.empty()) s += "; locals: " + join(local_names);
    return s;
  }
};

class Parser {
 public:
  Parser(const Source& src, const Scope& scope) : src_(src), scope_(scope), tokens_(tokenize(src)) {}

  bool at_end() const { return peek().kind == Tok::end; }
  const Token& peek() const { return tokens_[pos_]; }
  Token take() { return tokens_[pos_++]; }

  // The whole text as one expression.
  NodePtr parse_all() {
    if (at_end()) src_.fail(peek().column, std::string("empty ") + src_.kind);
    NodePtr n = parse_or();
    const Token& t = peek();
    if (t.kind == Tok::rparen) src_.fail(t.column, "unbalanced ')': there is no '(' to close");
    if (t.kind == Tok::assign) src_.fail(t.column, "unexpected '=' (to compare, write '==')");
    if (t.kind != Tok::end)
      src_.fail(t.column,
                "expected an operator or " + describe(tokens_.back(), src_) + " but found " + describe(t, src_));
    return n;
  }

  NodePtr parse_or() {
    NodePtr left = parse_and();
    while (peek().kind == Tok::name && peek().text == "or") left = logical(Node::Kind::logical_or, take(), left);
    return left;
  }

 private:
  NodePtr logical(Node::Kind kind, const Token& t, NodePtr& left) {
    NodePtr n = make_node(kind, t);
    n->kids.push_back(std::move(left));
    n->kids.push_back(kind == Node::Kind::logical_or ? parse_and() : parse_comparison());
    return n;
  }

  NodePtr binary(Op op, const Token& t, NodePtr& left, NodePtr right) {
    NodePtr n = make_node(Node::Kind::binary, t);
    n->op = op;
    n->kids.push_back(std::move(left));
    n->kids.push_back(std::move(right));
    return n;
  }

  bool peek_op(const char* a, const char* b = nullptr) const {
    const Token& t = peek();
    return t.kind == Tok::op && (t.text == a || (b && t.text == b));
  }

  NodePtr parse_and() {
    NodePtr left = parse_comparison();
    while (peek().kind == Tok::name && peek().text == "and") left = logical(Node::Kind::logical_and, take(), left);
    return left;
  }

  NodePtr parse_comparison() {
    NodePtr left = parse_sum();
    while (peek_op("<", ">") || peek_op("<=", ">=") || peek_op("==", "!=")) {
      const Token t = take();
      const Op op = t.text == "<"    ? Op::lt
                    : t.text == ">"  ? Op::gt
                    : t.text == "<=" ? Op::le
                    : t.text == ">=" ? Op::ge
                    : t.text == "==" ? Op::eq
                                     : Op::ne;
      left = binary(op, t, left, parse_sum());
    }
    return left;
  }

  NodePtr parse_sum() {
    NodePtr left = parse_product();
    while (peek_op("+", "-")) {
      const Token t = take();
      left = binary(t.text == "+" ? Op::add : Op::sub, t, left, parse_product());
    }
    return left;
  }

  NodePtr parse_product() {
    NodePtr left = parse_unary();
    while (peek_op("*", "/")) {
      const Token t = take();
      left = binary(t.text == "*" ? Op::mul : Op::div, t, left, parse_unary());
    }
    return left;
  }

  // Every recursion cycle of the parser passes through here.
  NodePtr parse_unary() {
    if (++depth_ > kMaxParseDepth) src_.fail(peek().column, std::string(src_.kind) + " too deeply nested");
    NodePtr n;
    if (peek_op("-", "+")) {
      const Token t = take();
      NodePtr operand = parse_unary();
      if (operand->kind == Node::Kind::skip) misplaced_skip(*operand);
      if (t.text == "+") {
        n = std::move(operand);
      } else {
        n = make_node(Node::Kind::negate, t);
        n->kids.push_back(std::move(operand));
      }
    } else {
      n = parse_power();
    }
    --depth_;
    return n;
  }

  NodePtr parse_power() {
    NodePtr base = parse_primary();
    if (!peek_op("^")) return base;
    const Token t = take();
    NodePtr n = make_node(Node::Kind::call, t);
    n->func = Func::pow;
    n->kids.push_back(std::move(base));
    n->kids.push_back(parse_unary());
    return n;
  }

  [[noreturn]] void misplaced_skip(const Node& n) const {
    src_.fail(n.column, src_.in_locals ? "'skip' is not allowed in a local definition"
                                       : "'skip' may only be a branch of an 'if' whose value is the result "
                                         "of the expression");
  }

  std::vector<NodePtr> parse_arguments(const Token& callee) {
    std::vector<NodePtr> args;
    const Token open = take();  // '('
    if (peek().kind == Tok::rparen) {
      take();
      return args;
    }
    for (;;) {
      args.push_back(parse_or());
      if (peek().kind == Tok::comma) {
        take();
        continue;
      }
      if (peek().kind == Tok::rparen) {
        take();
        return args;
      }
      src_.fail(peek().column, "expected ',' or ')' in the arguments of '" + callee.text + "' (opened at column " +
                                   std::to_string(open.column) + ") but found " + describe(peek(), src_));
    }
  }

  static std::string arguments(int n) { return std::to_string(n) + (n == 1 ? " argument" : " arguments"); }

  void check_arity(const Token& callee, size_t given, int wanted) const {
    if (static_cast<int>(given) != wanted)
      src_.fail(callee.column, "'" + callee.text + "' takes " + arguments(wanted) + " but " + std::to_string(given) +
                                   (given == 1 ? " was" : " were") + " given");
  }

  NodePtr parse_primary() {
    const Token t = peek();
    if (t.kind == Tok::number) {
      take();
      NodePtr n = make_node(Node::Kind::number, t);
      n->value = t.value;
      return n;
    }
    if (t.kind == Tok::lparen) {
      take();
      NodePtr n = parse_or();
      if (peek().kind != Tok::rparen)
        src_.fail(peek().column, "expected ')' to close the '(' at column " + std::to_string(t.column) + " but found " +
                                     describe(peek(), src_));
      take();
      return n;
    }
    if (t.kind != Tok::name || t.text == "and" || t.text == "or")
      src_.fail(t.column, "expected a number, name or '(' but found " + describe(t, src_));
    take();
    const bool call = peek().kind == Tok::lparen;
    if (t.text == "if") {
      if (!call) src_.fail(t.column, "'if' needs its arguments: if(condition, value if true, value if false)");
      std::vector<NodePtr> args = parse_arguments(t);
      check_arity(t, args.size(), 3);
      NodePtr n = make_node(Node::Kind::if_then_else, t);
      n->kids = std::move(args);
      return n;
    }
    if (const FunctionInfo* f = find_function(t.text)) {
      if (!call) src_.fail(t.column, "function '" + t.text + "' needs its arguments in parentheses");
      std::vector<NodePtr> args = parse_arguments(t);
      check_arity(t, args.size(), f->arity);
      NodePtr n = make_node(Node::Kind::call, t);
      n->func = f->func;
      n->kids = std::move(args);
      return n;
    }
    NodePtr n = resolve_name(t);
    if (call) {
      if (n) src_.fail(peek().column, "'" + t.text + "' is not a function, so it cannot be followed by '('");
      std::vector<std::string> names;
      for (const FunctionInfo& f : kFunctions) names.push_back(f.name);
      src_.fail(t.column, "unknown function '" + t.text + "'; functions: " + join(names) + ", if");
    }
    if (!n) src_.fail(t.column, "unknown name '" + t.text + "'; " + scope_.known_names());
    return n;
  }

  // A name that is not a function: a value, or null when unknown.
  NodePtr resolve_name(const Token& t) const {
    NodePtr n;
    if (t.text == "skip" || t.text == "Skip") return make_node(Node::Kind::skip, t);
    const int slot = scope_.vars.slot(t.text);
    if (slot >= 0) {
      n = make_node(Node::Kind::variable, t);
      n->slot = slot;
      return n;
    }
    double value = 0.0;
    bool constant = true;
    if (t.text == "pi") {
      value = math::pi<double>;
    } else if (auto c = scope_.constants.find(t.text); c != scope_.constants.end()) {
      value = c->second;
    } else if (auto l = scope_.constant_locals.find(t.text); l != scope_.constant_locals.end()) {
      value = l->second;
    } else if (auto r = scope_.runtime_locals.find(t.text); r != scope_.runtime_locals.end()) {
      n = make_node(Node::Kind::local, t);
      n->slot = r->second;
      return n;
    } else {
      constant = false;
    }
    if (!constant) return n;
    n = make_node(Node::Kind::number, t);
    n->value = value;
    return n;
  }

  const Source& src_;
  const Scope& scope_;
  std::vector<Token> tokens_;
  size_t pos_ = 0;
  int depth_ = 0;
};

// ---------------------------------------------------------------- checks and folding

// 'skip' is allowed only as a branch of an 'if' in result position.
void check_skip(const Node& n, const Source& src, bool result_position, bool if_branch) {
  if (n.kind == Node::Kind::skip) {
    if (result_position && if_branch && !src.in_locals) return;
    src.fail(n.column, src.in_locals ? "'skip' is not allowed in a local definition"
                                     : "'skip' may only be a branch of an 'if' whose value is the result "
                                       "of the expression");
  }
  for (size_t k = 0; k < n.kids.size(); ++k) {
    const bool branch = n.kind == Node::Kind::if_then_else && k > 0;
    check_skip(*n.kids[k], src, branch && result_position, branch);
  }
}

void make_number(Node& n, double value) {
  n.kind = Node::Kind::number;
  n.value = value;
  n.kids.clear();
}

void check_folded(Status s, const Node& n, const Source& src) {
  if (s != Status::ok) src.fail(n.column, std::string(status_text(s)) + " in '" + n.token + "' with constant operands");
}

bool is_number(const NodePtr& n) { return n->kind == Node::Kind::number; }

// Folds every operator whose operands are all constants. A constant 'if'
// condition (or a deciding left side of 'and'/'or') drops the untaken part
// without folding it, matching lazy evaluation.
void fold(NodePtr& n, const Source& src) {
  Node& node = *n;
  switch (node.kind) {
    case Node::Kind::number:
    case Node::Kind::variable:
    case Node::Kind::local:
    case Node::Kind::skip:
      return;
    case Node::Kind::negate:
      fold(node.kids[0], src);
      if (is_number(node.kids[0])) make_number(node, -node.kids[0]->value);
      return;
    case Node::Kind::binary: {
      fold(node.kids[0], src);
      fold(node.kids[1], src);
      if (!is_number(node.kids[0]) || !is_number(node.kids[1])) return;
      double r = 0.0;
      check_folded(apply_binary(node.op, node.kids[0]->value, node.kids[1]->value, &r), node, src);
      make_number(node, r);
      return;
    }
    case Node::Kind::call: {
      bool all = true;
      for (NodePtr& k : node.kids) {
        fold(k, src);
        all = all && is_number(k);
      }
      if (!all) return;
      double r = 0.0;
      const Status s = node.kids.size() == 1 ? apply_call1(node.func, node.kids[0]->value, &r)
                                             : apply_call2(node.func, node.kids[0]->value, node.kids[1]->value, &r);
      check_folded(s, node, src);
      make_number(node, r);
      return;
    }
    case Node::Kind::logical_and:
    case Node::Kind::logical_or: {
      const bool is_and = node.kind == Node::Kind::logical_and;
      fold(node.kids[0], src);
      if (is_number(node.kids[0])) {
        const bool left = node.kids[0]->value != 0.0;
        if (is_and && !left) return make_number(node, 0.0);
        if (!is_and && left) return make_number(node, 1.0);
      }
      fold(node.kids[1], src);
      if (is_number(node.kids[0]) && is_number(node.kids[1])) make_number(node, node.kids[1]->value != 0.0);
      return;
    }
    case Node::Kind::if_then_else: {
      fold(node.kids[0], src);
      if (is_number(node.kids[0])) {
        NodePtr taken = std::move(node.kids[node.kids[0]->value != 0.0 ? 1 : 2]);
        n = std::move(taken);  // destroys the 'if' node
        fold(n, src);
        return;
      }
      fold(node.kids[1], src);
      fold(node.kids[2], src);
      return;
    }
  }
}

void mark_used_locals(const Node& n, std::vector<bool>& used) {
  if (n.kind == Node::Kind::local) used[n.slot] = true;
  for (const NodePtr& k : n.kids) mark_used_locals(*k, used);
}

// ---------------------------------------------------------------- code generation

// True for nodes whose value is always 1 or 0 (comparisons, 'and', 'or').
bool gives_one_or_zero(const Node& n) {
  if (n.kind == Node::Kind::logical_and || n.kind == Node::Kind::logical_or) return true;
  return n.kind == Node::Kind::binary && n.op != Op::add && n.op != Op::sub && n.op != Op::mul && n.op != Op::div;
}

class CodeGenerator {
 public:
  void generate(const Node& n, const Source& src) {
    switch (n.kind) {
      case Node::Kind::number:
        emit(Op::push_const, constant_index(n.value, n, src), n, src, +1);
        return;
      case Node::Kind::variable:
        emit(Op::load_var, n.slot, n, src, +1);
        return;
      case Node::Kind::local:
        emit(Op::load_local, n.slot, n, src, +1);
        return;
      case Node::Kind::skip:
        emit(Op::skip, 0, n, src, +1);
        return;  // stands for the branch value
      case Node::Kind::negate:
        generate(*n.kids[0], src);
        emit(Op::neg, 0, n, src, 0);
        return;
      case Node::Kind::binary:
        generate(*n.kids[0], src);
        generate(*n.kids[1], src);
        emit(n.op, 0, n, src, -1);
        return;
      case Node::Kind::call:
        for (const NodePtr& k : n.kids) generate(*k, src);
        emit(n.kids.size() == 1 ? Op::call1 : Op::call2, static_cast<int>(n.func), n, src,
             1 - static_cast<int>(n.kids.size()));
        return;
      case Node::Kind::logical_and:
      case Node::Kind::logical_or: {
        generate(*n.kids[0], src);
        const int jump = emit(n.kind == Node::Kind::logical_and ? Op::and_jump : Op::or_jump, 0, n, src, -1);
        generate(*n.kids[1], src);
        if (!gives_one_or_zero(*n.kids[1])) emit(Op::to_bool, 0, n, src, 0);
        patch(jump);
        return;
      }
      case Node::Kind::if_then_else: {
        generate(*n.kids[0], src);
        const int to_else = emit(Op::jump_if_false, 0, n, src, -1);
        const int base = depth_;
        generate(*n.kids[1], src);
        const bool stops = n.kids[1]->kind == Node::Kind::skip;  // no jump needed after a skip
        const int to_end = stops ? -1 : emit(Op::jump, 0, n, src, 0);
        depth_ = base;
        patch(to_else);
        generate(*n.kids[2], src);
        if (!stops) patch(to_end);
        return;
      }
    }
  }

  // Stores the value on the stack into a local slot.
  void store_local(int slot, int column, const std::string& name, const Source& src) {
    Node n{Node::Kind::local, column, name, 0.0, slot, Op::add, Func::sin, {}};
    emit(Op::store_local, slot, n, src, -1);
  }

  std::vector<Instr> code;
  std::vector<InstrSource> sources;
  std::vector<double> constants;
  int max_depth = 0;

 private:
  int emit(Op op, int arg, const Node& n, const Source& src, int depth_change) {
    if (static_cast<int>(code.size()) >= kMaxIndex)
      src.fail(n.column, "expression too long (more than " + std::to_string(kMaxIndex) + " instructions)");
    depth_ += depth_change;
    if (depth_ > kMaxStack)
      src.fail(n.column, std::string(src.kind) + " too deeply nested (needs more than " + std::to_string(kMaxStack) +
                             " stack entries)");
    if (depth_ > max_depth) max_depth = depth_;
    code.push_back(Instr{op, 0, static_cast<std::int16_t>(arg)});
    sources.push_back(InstrSource{n.column, src.in_locals, n.token});
    return static_cast<int>(code.size()) - 1;
  }

  void patch(int jump) { code[jump].arg = static_cast<std::int16_t>(code.size()); }

  int constant_index(double v, const Node& n, const Source& src) {
    for (size_t i = 0; i < constants.size(); ++i)
      if (std::memcmp(&constants[i], &v, sizeof v) == 0) return static_cast<int>(i);
    if (static_cast<int>(constants.size()) >= kMaxIndex) src.fail(n.column, "too many constants");
    constants.push_back(v);
    return static_cast<int>(constants.size()) - 1;
  }

  int depth_ = 0;
};

}  // namespace

// ---------------------------------------------------------------- caller input

std::string name_problem(const std::string& name) {
  if (name.empty()) return "an empty name";
  if (!is_name_start(name[0])) return "a name that starts with neither a letter nor '_'";
  for (size_t k = 0; k < name.size(); ++k)
    if (!is_name_char(name[k]))
      return "a character other than a letter, digit or '_' at column " + std::to_string(k + 1);
  if (is_reserved(name)) return "a reserved word (if, and, or, skip, Skip, pi)";
  if (find_function(name)) return "the name of a function";
  return "";
}

namespace {

void check_caller_names(const VariableTable& vars, const std::map<std::string, double>& constants) {
  if (vars.names.size() > static_cast<size_t>(kMaxIndex))
    throw std::invalid_argument("expression compiler: too many variables");
  for (size_t i = 0; i < vars.names.size(); ++i) {
    const std::string& v = vars.names[i];
    if (!name_problem(v).empty())
      throw std::invalid_argument("expression compiler: '" + v + "' cannot be a variable name");
    if (vars.slot(v) != static_cast<int>(i))
      throw std::invalid_argument("expression compiler: variable '" + v + "' listed twice");
  }
  for (const auto& [name, value] : constants) {
    if (!name_problem(name).empty() || vars.slot(name) >= 0)
      throw std::invalid_argument("expression compiler: '" + name + "' cannot be a constant name");
    if (!std::isfinite(value))
      throw std::invalid_argument("expression compiler: constant '" + name + "' is not finite");
  }
}

// Parses "name = expression; ..." into `scope`, folding constant locals.
// Returns the run-time locals' definitions (indexed by slot).
std::vector<NodePtr> parse_locals(const Source& src, Scope& scope) {
  std::vector<NodePtr> runtime;
  Parser parser(src, scope);
  while (!parser.at_end()) {
    if (parser.peek().kind == Tok::semicolon) {  // empty definition, e.g. a trailing ';'
      parser.take();
      continue;
    }
    const Token name = parser.take();
    if (name.kind != Tok::name)
      src.fail(name.column, "expected a local name (as in 'kw=9.375') but found " + describe(name, src));
    const std::string& s = name.text;
    if (is_reserved(s)) src.fail(name.column, "'" + s + "' is reserved and cannot be a local name");
    if (find_function(s)) src.fail(name.column, "local '" + s + "' would shadow the function '" + s + "'");
    if (scope.vars.slot(s) >= 0) src.fail(name.column, "local '" + s + "' would shadow the variable '" + s + "'");
    if (scope.constants.count(s)) src.fail(name.column, "local '" + s + "' would shadow the constant '" + s + "'");
    if (scope.local_columns.count(s))
      src.fail(name.column, "local '" + s + "' is already defined at column " + std::to_string(scope.local_columns[s]));
    if (parser.peek().kind != Tok::assign)
      src.fail(parser.peek().column,
               "expected '=' after the local name '" + s + "' but found " + describe(parser.peek(), src));
    parser.take();
    if (parser.peek().kind == Tok::semicolon || parser.at_end())
      src.fail(parser.peek().column,
               "expected the value of local '" + s + "' but found " + describe(parser.peek(), src));
    NodePtr value = parser.parse_or();
    if (parser.peek().kind != Tok::semicolon && !parser.at_end())
      src.fail(parser.peek().column, "expected ';' or the end of the locals after the definition of '" + s +
                                         "' but found " + describe(parser.peek(), src));
    check_skip(*value, src, false, false);
    fold(value, src);
    scope.local_columns[s] = name.column;
    scope.local_names.push_back(s);
    if (value->kind == Node::Kind::number) {
      scope.constant_locals[s] = value->value;
    } else {
      const int slot = static_cast<int>(runtime.size());
      if (slot >= kMaxLocals)
        src.fail(name.column, "too many run-time locals (at most " + std::to_string(kMaxLocals) + ")");
      scope.runtime_locals[s] = slot;
      scope.runtime_local_columns.push_back(name.column);
      runtime.push_back(std::move(value));
    }
  }
  return runtime;
}

std::string local_name_of_slot(const Scope& scope, int slot) {
  for (const auto& [name, s] : scope.runtime_locals)
    if (s == slot) return name;
  return "?";
}

}  // namespace

Program compile(const std::string& expression, const VariableTable& vars,
                const std::map<std::string, double>& constants, const std::string& locals) {
  check_caller_names(vars, constants);
  Scope scope{vars, constants, {}, {}, {}, {}, {}};
  const Source locals_src{"locals", locals, true};
  std::vector<NodePtr> local_defs = parse_locals(locals_src, scope);

  const Source expr_src{"expression", expression, false};
  NodePtr root = Parser(expr_src, scope).parse_all();
  check_skip(*root, expr_src, true, false);
  fold(root, expr_src);

  // Run-time locals the expression needs, directly or through later locals.
  std::vector<bool> used(local_defs.size(), false);
  mark_used_locals(*root, used);
  for (int slot = static_cast<int>(local_defs.size()) - 1; slot >= 0; --slot)
    if (used[slot]) mark_used_locals(*local_defs[slot], used);

  CodeGenerator gen;
  for (size_t slot = 0; slot < local_defs.size(); ++slot) {
    if (!used[slot]) continue;
    gen.generate(*local_defs[slot], locals_src);
    gen.store_local(static_cast<int>(slot), scope.runtime_local_columns[slot],
                    local_name_of_slot(scope, static_cast<int>(slot)), locals_src);
  }
  gen.generate(*root, expr_src);
  return Program(expression, locals, std::move(gen.code), std::move(gen.sources), std::move(gen.constants),
                 gen.max_depth, static_cast<int>(local_defs.size()));
}

}  // namespace mfsd::expr
