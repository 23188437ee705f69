#pragma once
/// The format line of *VWRITE and *MSG (APDL_SCRIPTING §A.9, §A.14): a Fortran format `(...)`
/// with F, E, D, ES, G, I, A, X, T, P, '/', quoted text, Hollerith text, repeat counts and
/// groups; or a C-style line with %I %D %F %E %G %C %S %/ and printf flags, widths and precisions.
#include <stdexcept>
#include <string>
#include <vector>

#include "deck/parameters.h"

namespace impactfe::deck {

class FormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OutputFormat {
 public:
  /// Parses a format line; FormatError names what is wrong.
  static OutputFormat parse(const std::string& line);

  /// Formats one record: each data descriptor takes the next item. Fortran rules: when the items
  /// are used up, output stops at the next data descriptor (text before it is written); when the
  /// format ends with items left, it starts again on a new line from its last top-level group
  /// (or its beginning). C-style: items beyond the conversions are ignored. A number under A, or
  /// a text under F/E/G/I, gives blanks of the field width and a warning. Returns the lines.
  std::vector<std::string> format(const std::vector<Value>& items,
                                  std::vector<std::string>* warnings = nullptr) const;

  bool is_fortran() const { return fortran_; }
  /// Number of data descriptors in one pass of the format.
  int n_data() const;

  struct Edit {
    enum Kind { Text, Data, Skip, Slash, Tab, TabLeft, TabRight, Scale, Colon } kind = Text;
    std::string text;   // Text: literal; Data (C): printf flags
    char code = 0;      // Data: F E D G I A S(ES) ; C: i f e g c
    int width = -1;     // -1: not given
    int digits = -1;    // d (or m for Iw.m)
    int exponent = -1;  // e of Ew.dEe
    int n = 0;          // Skip/Tab/Scale count
  };

 private:
  /// One data item under its edit descriptor (a text under a numeric one, or a number under A
  /// or %C, is written as blanks with a warning).
  std::string data_field(const Edit& e, const Value& v, int scale,
                         std::vector<std::string>* warnings) const;

  bool fortran_ = true;
  std::vector<Edit> edits_;  // groups expanded
  std::size_t revert_at_ = 0;
};

/// Fortran edit descriptors, exposed for tests: Fw.d, Ew.d[Ee] (letter E or D, scale factor k),
/// ESw.d, Gw.d, Iw[.m], Aw (w < 0: the text's width).
std::string fortran_f(double x, int w, int d, int scale = 0);
std::string fortran_e(double x, int w, int d, int e = -1, int scale = 0, char letter = 'E');
std::string fortran_es(double x, int w, int d, int e = -1);
std::string fortran_g(double x, int w, int d, int e = -1, int scale = 0);
std::string fortran_i(double x, int w, int m = -1);
std::string fortran_a(const std::string& text, int w);

}  // namespace impactfe::deck
