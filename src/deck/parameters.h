#pragma once
/// The APDL parameter table (APDL_SCRIPTING §A.1, §A.6, §A.7): numeric and character scalars,
/// numeric ARRAY, CHAR arrays and TABLE arrays (up to three subscripts, column-major), with the
/// per-macro-level local parameters ARG1..AR99 (§A.13). The assignment entry points at the end
/// are the interface the other command groups (*GET, *VGET, POST26 VGET/VPUT) use to store into
/// and read from parameters.
#include <array>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace impactfe::deck {

/// The value of an expression or of one parameter entry: a number or a text.
using Value = std::variant<double, std::string>;
inline bool is_text(const Value& v) {
  return std::holds_alternative<std::string>(v);
}

/// StringArray is *DIM,Par,STRING: one text of up to IMAX characters per column and plane; the
/// row subscript is a character position in it, so Par(i,j) is the text of column j from
/// character i on.
enum class ParamType { Number, Text, Array, CharArray, Table, StringArray };
const char* param_type_name(ParamType type);

/// Longest text of a character scalar (*SET VALUE) and of a CHAR-array entry (§A.6).
inline constexpr std::size_t kMaxTextLength = 32;
inline constexpr std::size_t kMaxCharEntryLength = 8;
/// Longest text of a STRING array entry (*DIM: IMAX is rounded up to a multiple of 8, at most 248).
inline constexpr int kMaxStringArrayLength = 248;
/// Largest number of entries of one array (a typo in *DIM must not allocate gigabytes).
inline constexpr long long kMaxArrayEntries = 50'000'000;

/// One parameter. Arrays are 3-D in column-major (Fortran) order; unused extents are 1. A TABLE
/// also stores its index values: row 0, column 0 and plane 0, so its storage is
/// (imax+1)(jmax+1)(kmax+1) entries addressed from subscript 0.
struct Param {
  ParamType type = ParamType::Number;
  double number = 0.0;                   // Number
  std::string text;                      // Text
  int imax = 1, jmax = 1, kmax = 1;      // arrays
  std::vector<double> values;            // Array, Table
  std::vector<std::string> texts;        // CharArray
  std::array<std::string, 3> variables;  // Table: primary variables (Var1..Var3)

  bool is_array() const {
    return type == ParamType::Array || type == ParamType::CharArray || type == ParamType::Table ||
           type == ParamType::StringArray;
  }
  /// CHAR or STRING: entries are texts.
  bool is_character_array() const {
    return type == ParamType::CharArray || type == ParamType::StringArray;
  }
  /// Lowest valid subscript: 0 for a TABLE (its index row/column/plane), else 1.
  int low() const { return type == ParamType::Table ? 0 : 1; }
  bool in_range(int i, int j, int k) const {
    return i >= low() && i <= imax && j >= low() && j <= jmax && k >= low() && k <= kmax;
  }
  /// Storage index of (i, j, k); the subscripts must be in range. For a STRING array the index
  /// of the text of column j, plane k (i is the character position in it).
  std::size_t offset(int i, int j, int k) const;
  /// Entry (i, j, k) as a Value (a number, or the text of a CHAR entry).
  Value entry(int i, int j, int k) const;

  static Param scalar(double v);
  static Param character(std::string t);
  /// A zero-filled ARRAY / blank CHAR / TABLE of the given extents.
  static Param array(ParamType type, int imax, int jmax, int kmax);
};

/// Linear interpolation of a TABLE at primary-variable values (x, y, z) (§A.7): the row index
/// values are T(i,0,1), the column index values T(0,j,1), the plane index values T(0,0,k); a
/// value outside an index range takes the end value (no extrapolation).
double table_lookup(const Param& table, double x, double y, double z);

/// ARG1..ARG9 and AR10..AR99: local to each macro level (and to the top level).
bool is_local_name(std::string_view upper_name);

class Parameters {
 public:
  /// The parameter `name` (case-insensitive), searching the current local level for local names;
  /// nullptr when undefined.
  const Param* find(const std::string& name) const;
  Param* find(const std::string& name);
  /// Defines or replaces `name`.
  Param& define(const std::string& name, Param p);
  void set(const std::string& name, double value);
  void set_text(const std::string& name, const std::string& value);
  void erase(const std::string& name);
  /// The numeric scalar `name`; nullopt when undefined or not a number. An unset local
  /// (ARGn/ARnn) is 0, as MAPDL gives unset macro arguments.
  std::optional<double> get(const std::string& name) const;
  /// Global parameters in name order (for *STATUS, SAVE).
  const std::map<std::string, Param>& all() const { return globals_; }
  /// The local parameters of the current macro level.
  const std::map<std::string, Param>& locals() const { return locals_.back(); }

  /// Macro levels (*USE and macro calls): a new, empty set of local parameters.
  void push_level() { locals_.emplace_back(); }
  void pop_level() {
    if (locals_.size() > 1) locals_.pop_back();
  }
  /// /CLEAR: every global parameter, the angle unit and the random sequence back to their start;
  /// the local parameters of the macro calls running stay.
  void clear();

  bool degrees = false;  // *AFUN,DEG
  /// RAND/GDIS: a fixed seed, so a deck gives the same numbers on every run.
  mutable std::mt19937_64 random{20240611u};

 private:
  std::map<std::string, Param> globals_;
  std::vector<std::map<std::string, Param>> locals_{1};
};

/// The value MAPDL gives a parameter that is used in a numeric field but not defined: the
/// "tiny" 2^-100 ≈ 7.88860905221e-31 (APDL Programmer's Reference §3.6).
inline constexpr double kUndefinedParameterValue = 7.888609052210118e-31;

/// True for a legal parameter name: a letter (or a leading `_`, reserved for program parameters)
/// first, then letters, digits or '_', at most 32 characters.
bool is_parameter_name(std::string_view name);

/// Splits `NAME(s1,s2,s3)` into the name and the subscript texts; nullopt when `text` is not a
/// name optionally followed by one parenthesised list (blanks allowed before the parenthesis).
struct SubscriptedName {
  std::string name;  // upper case
  std::vector<std::string> subscripts;
  bool has_parentheses = false;
};
std::optional<SubscriptedName> split_subscripted_name(std::string_view text);

/// Number formatting of `%par%` substitution and of free-format output (§A.5, [A] S2): integral
/// values as integers, others in the shortest text that reads back to the same double, with an
/// upper-case exponent (0.25, 1.5E-06).
std::string format_number(double value);

// ---- assignment interface (shared with *GET, *VGET, POST26 VGET/VPUT) ---------------------------

class DeckReader;
struct Command;

/// Stores `value` into `target`: "NAME" (a numeric scalar, created or replaced) or
/// "NAME(i[,j[,k]])" (an element of an existing ARRAY or TABLE; subscripts are expressions).
/// Errors name the command: undefined array, subscript out of range, character array.
void assign_parameter(DeckReader& r, const Command& c, const std::string& target, double value);
/// The same for a text: a character scalar, or an element of a CHAR array (≤ 8 characters).
void assign_text_parameter(DeckReader& r, const Command& c, const std::string& target,
                           const std::string& value);
/// Fills an array column from the given start: "NAME(i)" or "NAME(i,j[,k])" (plain "NAME" =
/// NAME(1,1,1)); values go down the first subscript. An undefined NAME is created as an ARRAY
/// just long enough (as POST26 VGET does); an error when it is not numeric or too short.
void assign_vector(DeckReader& r, const Command& c, const std::string& target,
                   const std::vector<double>& values);
/// Reads `count` values down an array column from the given start (as *VPUT and POST26 VPUT
/// read). Error when the array is undefined, not numeric, or too short.
std::vector<double> read_vector(DeckReader& r, const Command& c, const std::string& source,
                                int count);
/// The values of a numeric array parameter's column from the element a field names: the array
/// (its first column from row 1), NAME(i) or NAME(i,j), down to the array's end (vme2 gives
/// EDLOAD's Par1 as TIME(1); RBE3 its slaves as SLV(1)). `what` names the field in errors.
std::vector<double> array_column(DeckReader& r, const Command& c, int field, const char* what);

/// *GET,Par,PARM,Name,TYPE / DIM: the type code of MAPDL (-1 undefined, 0 numeric scalar,
/// 1 numeric array, 2 table, 3 character scalar, 4 character array) and the extents of an array
/// (0 for a scalar).
struct ParameterInfo {
  int type = -1;
  int dims[3] = {0, 0, 0};
};
ParameterInfo parameter_info(DeckReader& r, const std::string& name);
/// Number of defined global parameters (PARM,,MAX) and of numeric scalars among them (BASIC).
std::pair<int, int> parameter_counts(DeckReader& r);

/// Position of an array element given in a command field ("NAME", "NAME(i)", "NAME(i,j,k)"):
/// the parameter and its subscripts (missing subscripts are 1). Error when `text` does not name
/// a defined array or a subscript is out of range.
struct ArrayPosition {
  std::string name;
  Param* param = nullptr;
  int i = 1, j = 1, k = 1;
};
ArrayPosition array_position(DeckReader& r, const Command& c, const std::string& text);

}  // namespace impactfe::deck
