#pragma once
// User expressions in scene files (initial.u_expr, ...): a small recursive-descent parser
// compiled once to a postfix program, evaluated without allocation.
//
//   numbers     1, 2.5, .5, 1e-3, 6.02E23
//   operators   + - * /, ^ (power, right-associative: 2^3^2 = 2^9), unary - and +;
//               -x^2 = -(x^2); parentheses
//   variables   x, y, t
//   constants   pi, e
//   functions   sin cos tan asin acos atan sinh cosh tanh exp log (natural) log10 sqrt abs
//               floor ceil  (one argument);  atan2(a,b) min(a,b) max(a,b) pow(a,b)
//
// Parse errors throw std::invalid_argument("position N: ...") with N the 1-based column.
#include <string>
#include <vector>

namespace refmap {

class Expression {
 public:
  Expression() = default;  ///< the empty expression, evaluates to 0
  /// Parses `text`; throws std::invalid_argument on a syntax error or unknown identifier.
  explicit Expression(const std::string& text);

  double eval(double x, double y, double t = 0.0) const;
  double operator()(double x, double y, double t = 0.0) const { return eval(x, y, t); }

  const std::string& text() const { return text_; }
  bool uses_time() const { return uses_t_; }  ///< true if `t` appears
  bool empty() const { return code_.empty(); }

  /// One instruction of the postfix program (public only so the parser can build it).
  struct Op {
    enum Kind : unsigned char { Const, X, Y, T, Neg, Add, Sub, Mul, Div, Pow, Fn1, Fn2 } kind;
    double value = 0.0;
    double (*f1)(double) = nullptr;
    double (*f2)(double, double) = nullptr;
  };
  static constexpr int max_stack = 64;

 private:
  std::string text_;
  std::vector<Op> code_;
  bool uses_t_ = false;
};

}  // namespace refmap
