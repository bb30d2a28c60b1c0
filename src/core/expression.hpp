#pragma once
// Scalar expressions of (x, y, z, t) given in decks, e.g. Gaussian pulses. Parsed once; constant
// expressions are folded so evaluating them per node costs nothing.
#include <memory>
#include <string>

namespace periadapt {

class Expression {
 public:
  Expression() = default;
  // Throws std::invalid_argument with the parser's message when `text` is malformed.
  explicit Expression(const std::string& text);
  Expression(const Expression& other);
  Expression& operator=(const Expression& other);
  ~Expression();

  double operator()(double x, double y, double z, double t) const;
  bool is_constant() const { return constant_; }
  bool depends_on_time() const { return uses_t_; }
  const std::string& text() const { return text_; }
  bool empty() const { return text_.empty(); }

 private:
  struct Impl;
  std::string text_;
  std::unique_ptr<Impl> impl_;
  bool constant_ = true;
  bool uses_t_ = false;
  double value_ = 0.0;
};

}  // namespace periadapt
