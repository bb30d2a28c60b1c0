#include "core/expression.hpp"

#include <muParser.h>

#include <numbers>
#include <stdexcept>

namespace periadapt {

namespace {
// muParser reads `x = 1` (and `+=` ...) as assigning the variable: a deck that meant `==` would
// get the assigned value instead of a condition.
bool has_assignment(const std::string& s) {
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s[k] != '=') continue;
    const char prev = k > 0 ? s[k - 1] : ' ', next = k + 1 < s.size() ? s[k + 1] : ' ';
    if (next == '=') {
      ++k;  // `==`
      continue;
    }
    if (prev != '<' && prev != '>' && prev != '!') return true;
  }
  return false;
}
}  // namespace

struct Expression::Impl {
  mu::Parser parser;
  mutable double x = 0, y = 0, z = 0, t = 0;
  explicit Impl(const std::string& text) {
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    parser.DefineVar("z", &z);
    parser.DefineVar("t", &t);
    parser.DefineConst("pi", std::numbers::pi);
    parser.SetExpr(text);
  }
};

Expression::Expression(const std::string& text) : text_(text) {
  if (has_assignment(text))
    throw std::invalid_argument("cannot parse expression '" + text +
                                "': '=' assigns a variable; compare with '==', '<=' or '>='");
  try {
    impl_ = std::make_unique<Impl>(text);
    const auto& used = impl_->parser.GetUsedVar();
    constant_ = used.empty();
    uses_t_ = used.count("t") > 0;
    value_ = impl_->parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    throw std::invalid_argument("cannot parse expression '" + text + "': " + e.GetMsg());
  }
}

Expression::Expression(const Expression& o) : text_(o.text_), constant_(o.constant_),
                                              uses_t_(o.uses_t_), value_(o.value_) {
  if (!o.text_.empty()) impl_ = std::make_unique<Impl>(o.text_);
}

Expression& Expression::operator=(const Expression& o) {
  if (this != &o) {
    text_ = o.text_;
    constant_ = o.constant_;
    uses_t_ = o.uses_t_;
    value_ = o.value_;
    impl_ = o.text_.empty() ? nullptr : std::make_unique<Impl>(o.text_);
  }
  return *this;
}

Expression::~Expression() = default;

double Expression::operator()(double x, double y, double z, double t) const {
  if (constant_ || !impl_) return value_;
  impl_->x = x;
  impl_->y = y;
  impl_->z = z;
  impl_->t = t;
  return impl_->parser.Eval();
}

}  // namespace periadapt
