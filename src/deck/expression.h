#pragma once
/// Scalar parameters and APDL expressions (APDL_SUBSET §1.9, APDL_SCRIPTING §A.3–A.4).
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace impactfe::deck {

/// Thrown by evaluate(); the caller turns it into an InputError with the command's location.
class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The scalar parameter table. Names are upper-cased; `*AFUN` selects radians or degrees.
class Parameters {
 public:
  void set(const std::string& name, double value);
  void erase(const std::string& name);
  std::optional<double> get(const std::string& name) const;
  bool degrees = false;  // *AFUN,DEG
  const std::map<std::string, double>& all() const { return values_; }

 private:
  std::map<std::string, double> values_;
};

/// True for a legal parameter name: a letter first, then letters, digits or '_', ≤ 32 chars.
bool is_parameter_name(std::string_view name);

/// Evaluates `+ - * / **`, parentheses, numbers in Fortran format, parameters and the functions
/// SIN COS TAN ASIN ACOS ATAN SQRT ABS EXP LOG LOG10 NINT MOD (MOD takes two arguments).
/// Throws ExpressionError naming the offending token.
double evaluate(std::string_view expression, const Parameters& parameters);

}  // namespace impactfe::deck
