// A problem with a user expression: a compile error (syntax, unknown name,
// misplaced skip, ...) or a run-time error met by Program::evaluate_host.
// The message names the source text, the 1-based column and what went wrong,
// e.g.  in expression "1 + * 2": column 5: expected a number, name or '(' but found '*'
#pragma once
#include <stdexcept>
#include <string>

namespace mfsd::expr {

class ExpressionError : public std::runtime_error {
 public:
  // `source_kind` is "expression" or "locals"; `source` the text in question.
  static ExpressionError compile_error(const std::string& source_kind, const std::string& source, int column,
                                       const std::string& reason) {
    return ExpressionError(
        "in " + source_kind + " \"" + source + "\": column " + std::to_string(column) + ": " + reason, source, column,
        reason);
  }

  ExpressionError(const std::string& message, const std::string& source, int column, const std::string& reason)
      : std::runtime_error(message), source_(source), column_(column), reason_(reason) {}

  const std::string& source() const { return source_; }  // the text the column refers to
  int column() const { return column_; }                 // 1-based; 0 when not tied to a column
  const std::string& reason() const { return reason_; }  // the message without source and column

 private:
  std::string source_;
  int column_;
  std::string reason_;
};

}  // namespace mfsd::expr
