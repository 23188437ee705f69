#pragma once
/// APDL expressions (APDL_SUBSET §1.9, APDL_SCRIPTING §A.3–A.4, APDL_MODELING §10.3): numbers in
/// Fortran format, quoted strings, parameters and array elements, table interpolation, the
/// operators + - * / ** < >, the built-in functions and the get functions of a host.
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "deck/parameters.h"

namespace impactfe::deck {

/// Thrown by evaluate(); the caller turns it into an InputError with the command's location.
class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Functions the grammar does not know by itself: the get functions (NX(n), NODE(x,y,z), UX(n),
/// NSEL(n), ...) answered from the deck state. `call` returns false when `name` is not one of
/// its functions; it throws ExpressionError for a bad use (wrong argument count, missing node).
class FunctionHost {
 public:
  virtual ~FunctionHost() = default;
  virtual bool call(const std::string& name, const std::vector<double>& args,
                    double& result) const = 0;
};

/// Evaluates an expression to a number or a text (a quoted string, a character parameter, a
/// CHAR-array entry). A name followed by parentheses is, in this order: an element of an array
/// parameter (`F(37,1,1)`, a TABLE interpolated at the subscript values), a built-in function,
/// a function of `functions`. Throws ExpressionError naming the offending token.
Value evaluate_value(std::string_view expression, const Parameters& parameters,
                     const FunctionHost* functions = nullptr);

/// Same, for a number (a text result is an error).
double evaluate(std::string_view expression, const Parameters& parameters,
                const FunctionHost* functions = nullptr);

/// Names of the built-in functions (SIN ... MAX), for *STATUS and name checks.
bool is_builtin_function(const std::string& upper_name);

}  // namespace impactfe::deck
