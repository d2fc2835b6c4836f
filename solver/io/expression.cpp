#include "solver/io/expression.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace refmap {
namespace {

struct Fn1Entry { const char* name; double (*f)(double); };
struct Fn2Entry { const char* name; double (*f)(double, double); };

double f_sin(double a) { return std::sin(a); }
double f_cos(double a) { return std::cos(a); }
double f_tan(double a) { return std::tan(a); }
double f_asin(double a) { return std::asin(a); }
double f_acos(double a) { return std::acos(a); }
double f_atan(double a) { return std::atan(a); }
double f_sinh(double a) { return std::sinh(a); }
double f_cosh(double a) { return std::cosh(a); }
double f_tanh(double a) { return std::tanh(a); }
double f_exp(double a) { return std::exp(a); }
double f_log(double a) { return std::log(a); }
double f_log10(double a) { return std::log10(a); }
double f_sqrt(double a) { return std::sqrt(a); }
double f_abs(double a) { return std::fabs(a); }
double f_floor(double a) { return std::floor(a); }
double f_ceil(double a) { return std::ceil(a); }
double f_atan2(double a, double b) { return std::atan2(a, b); }
double f_min(double a, double b) { return std::fmin(a, b); }
double f_max(double a, double b) { return std::fmax(a, b); }
double f_pow(double a, double b) { return std::pow(a, b); }

constexpr Fn1Entry kFn1[] = {
    {"sin", f_sin},     {"cos", f_cos},   {"tan", f_tan},     {"asin", f_asin}, {"acos", f_acos},
    {"atan", f_atan},   {"sinh", f_sinh}, {"cosh", f_cosh},   {"tanh", f_tanh}, {"exp", f_exp},
    {"log", f_log},     {"log10", f_log10}, {"sqrt", f_sqrt}, {"abs", f_abs},   {"floor", f_floor},
    {"ceil", f_ceil}};
constexpr Fn2Entry kFn2[] = {{"atan2", f_atan2}, {"min", f_min}, {"max", f_max}, {"pow", f_pow}};

using Op = Expression::Op;

class Parser {
 public:
  Parser(const std::string& s, std::vector<Op>& code, bool& uses_t) : s_(s), code_(code), uses_t_(uses_t) {}

  void parse() {
    skip_ws();
    if (pos_ >= s_.size()) fail(pos_, "empty expression");
    expr();
    skip_ws();
    if (pos_ < s_.size()) {
      if (s_[pos_] == ')') fail(pos_, "unbalanced ')'");
      fail(pos_, std::string("expected an operator, got '") + s_[pos_] + "'");
    }
  }

 private:
  [[noreturn]] void fail(std::size_t at, const std::string& what) const {
    throw std::invalid_argument("position " + std::to_string(at + 1) + ": " + what);
  }
  void skip_ws() { while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_; }
  bool accept(char c) {
    skip_ws();
    if (pos_ < s_.size() && s_[pos_] == c) { ++pos_; return true; }
    return false;
  }
  void emit(Op::Kind k, double v = 0.0) { Op op{}; op.kind = k; op.value = v; code_.push_back(op); }

  // expr := term (('+'|'-') term)*
  void expr() {
    term();
    for (;;) {
      if (accept('+')) { term(); emit(Op::Add); }
      else if (accept('-')) { term(); emit(Op::Sub); }
      else return;
    }
  }
  // term := unary (('*'|'/') unary)*
  void term() {
    unary();
    for (;;) {
      if (accept('*')) { unary(); emit(Op::Mul); }
      else if (accept('/')) { unary(); emit(Op::Div); }
      else return;
    }
  }
  // unary := ('-'|'+') unary | power
  void unary() {
    if (++depth_ > 200) fail(pos_, "expression nested too deeply");
    if (accept('-')) { unary(); emit(Op::Neg); }
    else if (accept('+')) { unary(); }
    else power();
    --depth_;
  }
  // power := primary ('^' unary)?      (right-associative through unary -> power)
  void power() {
    primary();
    if (accept('^')) { unary(); emit(Op::Pow); }
  }
  void primary() {
    skip_ws();
    if (pos_ >= s_.size()) fail(pos_, "unexpected end of expression");
    const char c = s_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') { number(); return; }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') { identifier(); return; }
    if (c == '(') {
      ++pos_;
      expr();
      if (!accept(')')) fail(pos_, "expected ')'");
      return;
    }
    fail(pos_, std::string("unexpected '") + c + "'");
  }
  void number() {
    const std::size_t start = pos_;
    std::size_t p = pos_;
    bool digits = false;
    while (p < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p]))) { ++p; digits = true; }
    if (p < s_.size() && s_[p] == '.') {
      ++p;
      while (p < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p]))) { ++p; digits = true; }
    }
    if (!digits) fail(start, "malformed number");
    if (p < s_.size() && (s_[p] == 'e' || s_[p] == 'E')) {
      std::size_t q = p + 1;
      if (q < s_.size() && (s_[q] == '+' || s_[q] == '-')) ++q;
      if (q < s_.size() && std::isdigit(static_cast<unsigned char>(s_[q]))) {
        while (q < s_.size() && std::isdigit(static_cast<unsigned char>(s_[q]))) ++q;
        p = q;
      } else {
        fail(p, "malformed exponent in number");
      }
    }
    double v = 0.0;
    auto [end, ec] = std::from_chars(s_.data() + start, s_.data() + p, v);
    if (ec == std::errc::result_out_of_range) fail(start, "number out of range");
    if (ec != std::errc() || end != s_.data() + p) fail(start, "malformed number");
    pos_ = p;
    emit(Op::Const, v);
  }
  void identifier() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
    const std::string name = s_.substr(start, pos_ - start);
    skip_ws();
    const bool call = pos_ < s_.size() && s_[pos_] == '(';
    if (!call) {
      if (name == "x") emit(Op::X);
      else if (name == "y") emit(Op::Y);
      else if (name == "t") { emit(Op::T); uses_t_ = true; }
      else if (name == "pi") emit(Op::Const, std::numbers::pi);
      else if (name == "e") emit(Op::Const, std::numbers::e);
      else {
        for (const auto& f : kFn1) if (name == f.name) fail(start, "function '" + name + "' needs an argument: " + name + "(...)");
        for (const auto& f : kFn2) if (name == f.name) fail(start, "function '" + name + "' needs two arguments: " + name + "(a, b)");
        fail(start, "unknown identifier '" + name + "' (variables: x, y, t; constants: pi, e)");
      }
      return;
    }
    int arity = 0;
    double (*f1)(double) = nullptr;
    double (*f2)(double, double) = nullptr;
    for (const auto& f : kFn1) if (name == f.name) { f1 = f.f; arity = 1; }
    for (const auto& f : kFn2) if (name == f.name) { f2 = f.f; arity = 2; }
    if (arity == 0) fail(start, "unknown function '" + name + "'");
    ++pos_;  // '('
    int nargs = 0;
    skip_ws();
    if (pos_ < s_.size() && s_[pos_] == ')') {
      ++pos_;
    } else {
      for (;;) {
        expr();
        ++nargs;
        if (accept(',')) continue;
        if (accept(')')) break;
        fail(pos_, "expected ',' or ')' in the arguments of '" + name + "'");
      }
    }
    if (nargs != arity)
      fail(start, "function '" + name + "' takes " + std::to_string(arity) + " argument" + (arity == 1 ? "" : "s") +
                      ", got " + std::to_string(nargs));
    Op op{};
    op.kind = arity == 1 ? Op::Fn1 : Op::Fn2;
    op.f1 = f1;
    op.f2 = f2;
    code_.push_back(op);
  }

  const std::string& s_;
  std::vector<Op>& code_;
  bool& uses_t_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace

Expression::Expression(const std::string& text) : text_(text) {
  Parser(text_, code_, uses_t_).parse();
  // stack depth check, so eval can use a fixed-size stack
  int depth = 0, max_depth = 0;
  for (const Op& op : code_) {
    switch (op.kind) {
      case Op::Const: case Op::X: case Op::Y: case Op::T: ++depth; break;
      case Op::Neg: case Op::Fn1: break;
      default: --depth; break;
    }
    max_depth = depth > max_depth ? depth : max_depth;
  }
  if (max_depth > max_stack) throw std::invalid_argument("expression too complex (evaluation stack > 64)");
}

double Expression::eval(double x, double y, double t) const {
  if (code_.empty()) return 0.0;
  double st[max_stack];
  int n = 0;
  for (const Op& op : code_) {
    switch (op.kind) {
      case Op::Const: st[n++] = op.value; break;
      case Op::X: st[n++] = x; break;
      case Op::Y: st[n++] = y; break;
      case Op::T: st[n++] = t; break;
      case Op::Neg: st[n - 1] = -st[n - 1]; break;
      case Op::Add: --n; st[n - 1] += st[n]; break;
      case Op::Sub: --n; st[n - 1] -= st[n]; break;
      case Op::Mul: --n; st[n - 1] *= st[n]; break;
      case Op::Div: --n; st[n - 1] /= st[n]; break;
      case Op::Pow: --n; st[n - 1] = std::pow(st[n - 1], st[n]); break;
      case Op::Fn1: st[n - 1] = op.f1(st[n - 1]); break;
      case Op::Fn2: --n; st[n - 1] = op.f2(st[n - 1], st[n]); break;
    }
  }
  return st[0];
}

}  // namespace refmap
