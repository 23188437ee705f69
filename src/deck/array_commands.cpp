// Vector commands (APDL_SCRIPTING §A.8, APDL_MODELING §10.2): *VFILL, *VOPER, *VFUN, *VSCFUN
// and the settings *VFACT, *VMASK, *VLEN, *VCUM, *VABS, *VCOL, *VSTAT.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

#include "deck/vector_support.h"

namespace impactfe::deck {

// ---- shared machinery
// ------------------------------------------------------------------------------

double VectorOperand::at(long long row, int dj) const {
  if (!column) return constant;
  return pos.param->values[pos.param->offset(pos.i + static_cast<int>(row), pos.j + dj, pos.k)];
}

VectorOperand vector_operand(DeckReader& r, const Command& c, int f) {
  const std::string& t = c.text(f);
  if (t.empty()) r.fail(c, fmt::format("field {}: operand missing", f));
  VectorOperand op;
  if (const auto n = split_subscripted_name(t)) {
    const Param* p = r.params.find(n->name);
    if (p != nullptr && p->is_array()) {
      op.column = true;
      op.pos = array_position(r, c, t);
      if (p->is_character_array())
        r.fail(c, fmt::format("field {}: {} is a {} array (numbers needed)", f, n->name,
                              param_type_name(p->type)));
      return op;
    }
  }
  op.constant = r.eval(c, t);
  return op;
}

void VectorPass::store(long long k, double value, int dj) const {
  double v = settings.factor_result * value;
  if (settings.abs_result) v = std::fabs(v);
  double& slot =
      out.param->values[out.param->offset(out.i + static_cast<int>(row(k)), out.j + dj, out.k)];
  slot = settings.cumulate ? slot + v : v;
}

VectorPass begin_vector_pass(DeckReader& r, const Command& c, int f, long long default_rows,
                             int create_cols) {
  VectorPass p;
  p.settings = r.scripting.vector_settings;
  r.scripting.vector_settings = VectorSettings{};
  p.step = std::max(1, p.settings.row_increment);
  p.result = c.text(f);
  if (p.result.empty()) r.fail(c, fmt::format("field {}: result parameter missing", f));
  const auto n = split_subscripted_name(p.result);
  if (!n) r.fail(c, fmt::format("'{}' is not an array name or element", p.result));
  if (r.params.find(n->name) == nullptr) {
    const long long rows = p.settings.n_rows ? *p.settings.n_rows : default_rows;
    if (rows <= 0) r.fail(c, fmt::format("array {} is not defined (*DIM it first)", n->name));
    int start[2] = {1, 1};
    for (std::size_t k = 0; k < n->subscripts.size() && k < 2; ++k)
      start[k] = static_cast<int>(std::lround(r.eval(c, n->subscripts[k])));
    if (start[0] < 1 || start[1] < 1) r.fail(c, fmt::format("bad start element {}", p.result));
    const long long imax = start[0] + (rows - 1) * p.step;
    if (imax > kMaxArrayEntries) r.fail(c, "result array too large");
    if (!is_parameter_name(n->name)) r.fail(c, fmt::format("'{}' is not a valid name", n->name));
    r.params.define(n->name, Param::array(ParamType::Array, static_cast<int>(imax),
                                          start[1] + create_cols - 1, 1));
    Log::info("{}:{}: {}: array {} created ({} x {})", c.where.file, c.where.line, c.name, n->name,
              imax, start[1] + create_cols - 1);
  }
  p.out = array_position(r, c, p.result);
  if (p.out.param->is_character_array())
    r.fail(c, fmt::format("{} is a {} array: numbers cannot be stored in it", n->name,
                          param_type_name(p.out.param->type)));
  const long long avail = (p.out.param->imax - p.out.i) / p.step + 1;
  p.rows = p.settings.n_rows ? *p.settings.n_rows : avail;
  if (p.rows > avail)
    r.fail(c, fmt::format("{} has room for {} rows from {}, {} requested", n->name, avail, p.result,
                          p.rows));
  if (p.out.j + create_cols - 1 > p.out.param->jmax)
    r.fail(c, fmt::format("{} needs {} columns from column {}, it has {}", n->name, create_cols,
                          p.out.j, p.out.param->jmax));
  p.active.assign(static_cast<std::size_t>(p.rows), 1);
  if (!p.settings.mask.empty()) {
    const ArrayPosition m = array_position(r, c, p.settings.mask);
    if (m.param->is_character_array()) r.fail(c, "the *VMASK array is a CHAR array");
    for (long long k = 0; k < p.rows; ++k) {
      const long long mi = m.i + p.row(k);
      if (mi <= m.param->imax)  // a short mask counts as true beyond its end
        p.active[static_cast<std::size_t>(k)] =
            m.param->values[m.param->offset(static_cast<int>(mi), m.j, m.k)] > 0.0;
    }
  }
  return p;
}

namespace {

void need_rows(DeckReader& r, const Command& c, const VectorOperand& op, const VectorPass& p,
               const char* name, int cols = 1) {
  if (!op.column) return;
  const long long needed = p.row(p.rows - 1) + 1;
  if (p.rows > 0 && needed > op.length())
    r.fail(c, fmt::format("{} ({}) has {} rows from its start, {} needed", name, op.pos.name,
                          op.length(), needed));
  if (op.pos.j + cols - 1 > op.pos.param->jmax)
    r.fail(c, fmt::format("{} ({}) needs {} columns from column {}", name, op.pos.name, cols,
                          op.pos.j));
}

std::vector<double> gather(const VectorOperand& op, const VectorPass& p, int which, int dj = 0) {
  std::vector<double> v(static_cast<std::size_t>(p.rows));
  for (long long k = 0; k < p.rows; ++k) {
    const double x = op.at(p.row(k), dj);
    v[static_cast<std::size_t>(k)] = which == 1 ? p.in1(x) : which == 2 ? p.in2(x) : p.in3(x);
  }
  return v;
}

void store_all(const VectorPass& p, const std::vector<double>& v, int dj = 0) {
  for (long long k = 0; k < p.rows; ++k)
    if (p.active[static_cast<std::size_t>(k)]) p.store(k, v[static_cast<std::size_t>(k)], dj);
}

double angle_in(const DeckReader& r) {
  return r.params.degrees ? std::numbers::pi / 180.0 : 1.0;
}

/// d y / d x on a column (x ascending): central differences at interior points (values at the
/// half-interval midpoints, APDL theory §"integration and differentiation procedures"), ends by
/// linear extrapolation of the two nearest derivatives.
std::vector<double> derivative(DeckReader& r, const Command& c, const std::vector<double>& y,
                               const std::vector<double>& x) {
  const std::size_t n = y.size();
  std::vector<double> d(n, 0.0);
  if (n < 2) r.fail(c, "a derivative needs at least two rows");
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (!(x[i + 1] > x[i])) r.fail(c, fmt::format("Par2 is not ascending at row {}", i + 2));
  if (n == 2) {
    d[0] = d[1] = (y[1] - y[0]) / (x[1] - x[0]);
    return d;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) d[i] = (y[i + 1] - y[i - 1]) / (x[i + 1] - x[i - 1]);
  d[0] = d[1] + (d[2] - d[1]) * (x[0] - x[1]) / (x[2] - x[1]);
  d[n - 1] = d[n - 2] + (d[n - 2] - d[n - 3]) * (x[n - 1] - x[n - 2]) / (x[n - 2] - x[n - 3]);
  return d;
}

/// ∫ y dx from the first row (trapezoid rule) plus `start`.
std::vector<double> integral(const std::vector<double>& y, const std::vector<double>& x,
                             double start) {
  std::vector<double> s(y.size(), start);
  for (std::size_t i = 1; i < y.size(); ++i)
    s[i] = s[i - 1] + 0.5 * (y[i] + y[i - 1]) * (x[i] - x[i - 1]);
  return s;
}

void cmd_vfill(DeckReader& r, const Command& c) {
  // *VFILL,ParR,Func,CON1..CON10 (§A.8)
  const std::string func = r.label(c, 2);
  if (func == "DATA") {
    std::vector<double> values;
    for (int k = 3; k <= std::min(c.n_fields(), 12); ++k) {
      if (c.blank(k)) break;  // values after the first blank CON are ignored
      values.push_back(r.real(c, k, 0.0));
    }
    r.scripting.vector_settings = VectorSettings{};
    assign_vector(r, c, c.text(1), values);
    return;
  }
  VectorPass p = begin_vector_pass(r, c, 1, 0);
  std::vector<double> v(static_cast<std::size_t>(p.rows));
  if (func == "RAMP") {
    const double a = r.real(c, 3, 0.0), b = r.real(c, 4, 0.0);
    for (long long k = 0; k < p.rows; ++k)
      v[static_cast<std::size_t>(k)] = a + static_cast<double>(k) * b;
  } else if (func == "RAND") {
    const double lo = r.real(c, 3, 0.0), hi = r.real(c, 4, 1.0);
    if (!(hi >= lo)) r.fail(c, "RAND: upper bound below the lower bound");
    std::uniform_real_distribution<double> dist(lo, hi);
    for (auto& x : v) x = dist(r.params.random);
  } else if (func == "GDIS") {
    const double mean = r.real(c, 3, 0.0), sd = r.real(c, 4, 1.0);
    if (sd < 0.0) r.fail(c, "GDIS: negative standard deviation");
    std::normal_distribution<double> dist(mean, sd);
    for (auto& x : v) x = sd == 0.0 ? mean : dist(r.params.random);
  } else {
    r.fail(c, fmt::format("function '{}' is not supported (DATA, RAMP, RAND, GDIS)", c.text(2)));
  }
  store_all(p, v);
}

double vfun_value(DeckReader& r, const Command& c, const std::string& f, double x, double con1,
                  long long row) {
  const double to_rad = angle_in(r);
  auto domain = [&](bool ok) {
    if (!ok) r.fail(c, fmt::format("{} of {} (row {}) is undefined", f, format_number(x), row + 1));
  };
  if (f == "COPY") return x;
  if (f == "ABS") return std::fabs(x);
  if (f == "SIN") return std::sin(x * to_rad);
  if (f == "COS") return std::cos(x * to_rad);
  if (f == "TAN") return std::tan(x * to_rad);
  if (f == "ASIN" || f == "ACOS") {
    domain(std::fabs(x) <= 1.0);
    return (f == "ASIN" ? std::asin(x) : std::acos(x)) / to_rad;
  }
  if (f == "ATAN") return std::atan(x) / to_rad;
  if (f == "SINH") return std::sinh(x);
  if (f == "COSH") return std::cosh(x);
  if (f == "TANH") return std::tanh(x);
  if (f == "EXP") return std::exp(x);
  if (f == "LOG" || f == "LOG10") {
    domain(x > 0.0);
    return f == "LOG" ? std::log(x) : std::log10(x);
  }
  if (f == "SQRT") {
    domain(x >= 0.0);
    return std::sqrt(x);
  }
  if (f == "NINT") return std::round(x);
  if (f == "NOT") return x <= 0.0 ? 1.0 : 0.0;
  if (f == "PWR") return x < 0.0 ? -std::pow(-x, con1) : std::pow(x, con1);
  r.fail(c, fmt::format("function '{}' is not supported", f));
}

/// Principal stresses of rows (SX SY SZ SXY SYZ SXZ) → S1 S2 S3 SINT SEQV.
std::array<double, 5> principal(const std::array<double, 6>& s) {
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(m, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d ev = es.eigenvalues();  // ascending
  const double s1 = ev(2), s2 = ev(1), s3 = ev(0);
  const double seqv =
      std::sqrt(0.5 * ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)));
  return {s1, s2, s3, s1 - s3, seqv};
}

void cmd_vfun(DeckReader& r, const Command& c) {
  // *VFUN,ParR,Func,Par1,CON1,CON2,CON3
  const std::string f = r.label(c, 2);
  const VectorOperand a = vector_operand(r, c, 3);
  if (!a.column) r.fail(c, "Par1 must be an array element");
  if (f == "PRIN") {
    VectorPass p = begin_vector_pass(r, c, 1, a.length(), 5);
    need_rows(r, c, a, p, "Par1", 6);
    for (long long k = 0; k < p.rows; ++k) {
      if (!p.active[static_cast<std::size_t>(k)]) continue;
      std::array<double, 6> s{};
      for (int j = 0; j < 6; ++j) s[static_cast<std::size_t>(j)] = p.in1(a.at(p.row(k), j));
      const auto out = principal(s);
      for (int j = 0; j < 5; ++j) p.store(k, out[static_cast<std::size_t>(j)], j);
    }
    return;
  }
  VectorPass p = begin_vector_pass(r, c, 1, a.length());
  need_rows(r, c, a, p, "Par1");
  std::vector<double> x = gather(a, p, 1);
  if (f == "ASORT" || f == "DSORT") {
    p.settings.cumulate = false;  // mask and *VCUM do not apply to sorting (§10.2)
    std::sort(x.begin(), x.end());
    if (f == "DSORT") std::reverse(x.begin(), x.end());
    for (long long k = 0; k < p.rows; ++k) p.store(k, x[static_cast<std::size_t>(k)]);
    return;
  }
  if (f == "COMP" || f == "EXPA") {
    // COMP: the rows the mask selects, packed; EXPA: successive values into the selected rows.
    std::vector<double> out(x.size(), 0.0);
    std::size_t next = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (!p.active[k]) continue;
      if (f == "COMP")
        out[next++] = x[k];
      else
        out[k] = x[next++];
    }
    for (long long k = 0; k < p.rows; ++k) p.store(k, out[static_cast<std::size_t>(k)]);
    return;
  }
  if (f == "DIRCOS" || f == "EULER" || f == "TANG" || f == "NORM" || f == "LOCAL" || f == "GLOBAL")
    r.fail(c, fmt::format("function {} is not supported", f));
  const double con1 = r.real(c, 4, 0.0);
  std::vector<double> out(x.size());
  for (std::size_t k = 0; k < x.size(); ++k)
    out[k] = p.active[k] ? vfun_value(r, c, f, x[k], con1, static_cast<long long>(k)) : 0.0;
  store_all(p, out);
}

double compare_op(const std::string& op, double a, double b) {
  if (op == "LT") return a < b;
  if (op == "LE") return a <= b;
  if (op == "EQ") return a == b;
  if (op == "NE") return a != b;
  if (op == "GE") return a >= b;
  return a > b;  // GT
}

void cmd_voper(DeckReader& r, const Command& c) {
  // *VOPER,ParR,Par1,Oper,Par2,CON1,CON2
  const std::string op = r.label(c, 3);
  const VectorOperand a = vector_operand(r, c, 2);
  const VectorOperand b = c.blank(4) ? VectorOperand{} : vector_operand(r, c, 4);
  const long long len = a.column ? a.length() : b.column ? b.length() : 0;
  const bool three = op == "CROSS";
  VectorPass p = begin_vector_pass(r, c, 1, len, three ? 3 : 1);
  const int cols = op == "DOT" || op == "CROSS" ? 3 : 1;
  need_rows(r, c, a, p, "Par1", cols);
  if (op != "GATH" && op != "SCAT") need_rows(r, c, b, p, "Par2", cols);
  const auto x = gather(a, p, 1);
  const auto y = gather(b, p, 2);
  const std::size_t n = x.size();
  std::vector<double> out(n, 0.0);
  if (op == "ADD" || op == "SUB" || op == "MULT" || op == "DIV" || op == "MIN" || op == "MAX" ||
      op == "ATN2") {
    for (std::size_t k = 0; k < n; ++k) {
      const double u = x[k], v = y[k];
      out[k] = op == "ADD"    ? u + v
               : op == "SUB"  ? u - v
               : op == "MULT" ? u * v
               : op == "DIV"  ? (v == 0.0 ? 0.0 : u / v)  // x/0 → 0 (§10.2)
               : op == "MIN"  ? std::min(u, v)
               : op == "MAX"  ? std::max(u, v)
                              : std::atan2(u, v) / angle_in(r);
    }
  } else if (op == "LT" || op == "LE" || op == "EQ" || op == "NE" || op == "GE" || op == "GT") {
    for (std::size_t k = 0; k < n; ++k) out[k] = compare_op(op, x[k], y[k]);
  } else if (op == "DER1" || op == "DER2") {
    if (!b.column) r.fail(c, "Par2 (the variable) must be an array element");
    out = derivative(r, c, x, y);
    if (op == "DER2") out = derivative(r, c, out, y);
  } else if (op == "INT1" || op == "INT2") {
    if (!b.column) r.fail(c, "Par2 (the variable) must be an array element");
    out = integral(x, y, r.real(c, 5, 0.0));
    if (op == "INT2") out = integral(out, y, r.real(c, 6, 0.0));
  } else if (op == "DOT") {
    for (std::size_t k = 0; k < n; ++k) {
      double s = 0.0;
      for (int j = 0; j < 3; ++j)
        s += p.in1(a.at(p.row(static_cast<long long>(k)), j)) *
             p.in2(b.at(p.row(static_cast<long long>(k)), j));
      out[k] = s;
    }
  } else if (op == "CROSS") {
    for (long long k = 0; k < p.rows; ++k) {
      if (!p.active[static_cast<std::size_t>(k)]) continue;
      Eigen::Vector3d u, v;
      for (int j = 0; j < 3; ++j) {
        u(j) = p.in1(a.at(p.row(k), j));
        v(j) = p.in2(b.at(p.row(k), j));
      }
      const Eigen::Vector3d w = u.cross(v);
      for (int j = 0; j < 3; ++j) p.store(k, w(j), j);
    }
    return;
  } else if (op == "GATH" || op == "SCAT") {
    // GATH: ParR(k) = Par1(Par2(k)); SCAT: ParR(Par2(k)) = Par1(k) (positions from Par1's start).
    if (!a.column || !b.column) r.fail(c, "Par1 and Par2 must be array elements");
    need_rows(r, c, b, p, "Par2");
    for (long long k = 0; k < p.rows; ++k) {
      if (!p.active[static_cast<std::size_t>(k)]) continue;
      const long long pos = std::llround(b.at(p.row(k))) - 1;
      if (op == "GATH") {
        if (pos < 0 || pos >= a.length())
          r.fail(c, fmt::format("GATH: position {} outside Par1", pos + 1));
        p.store(k, p.in1(a.at(pos)));
      } else {
        if (pos < 0 || pos >= p.rows)
          r.fail(c, fmt::format("SCAT: position {} outside ParR", pos + 1));
        p.store(pos, p.in1(a.at(p.row(k))));
      }
    }
    return;
  } else if (op == "LOCAL" || op == "GLOBAL") {
    r.fail(c, fmt::format("{} (coordinate transformation) is not supported", op));
  } else {
    r.fail(c, fmt::format("operation '{}' is not supported", c.text(3)));
  }
  store_all(p, out);
}

void cmd_vscfun(DeckReader& r, const Command& c) {
  // *VSCFUN,ParR,Func,Par1: a scalar from the (unmasked) rows of Par1.
  const std::string f = r.label(c, 2);
  const VectorOperand a = vector_operand(r, c, 3);
  if (!a.column) r.fail(c, "Par1 must be an array element");
  // The pass runs over Par1 (the result is a scalar).
  VectorSettings s = r.scripting.vector_settings;
  r.scripting.vector_settings = VectorSettings{};
  const int step = std::max(1, s.row_increment);
  const long long avail = (a.length() - 1) / step + 1;
  const long long rows = s.n_rows ? *s.n_rows : avail;
  if (rows > avail) r.fail(c, fmt::format("Par1 has {} rows, {} requested", avail, rows));
  std::vector<double> x;
  std::vector<long long> index;  // 1-based row index from the start
  ArrayPosition mask;
  if (!s.mask.empty()) mask = array_position(r, c, s.mask);
  for (long long k = 0; k < rows; ++k) {
    if (mask.param != nullptr) {
      const long long mi = mask.i + k * step;
      if (mi <= mask.param->imax &&
          mask.param->values[mask.param->offset(static_cast<int>(mi), mask.j, mask.k)] <= 0.0)
        continue;
    }
    const double v = s.factor1 * (s.abs1 ? std::fabs(a.at(k * step)) : a.at(k * step));
    x.push_back(v);
    index.push_back(k * step + 1);
  }
  const double n = static_cast<double>(x.size());
  double result = 0.0;
  const double sum = std::accumulate(x.begin(), x.end(), 0.0);
  const double mean = n > 0 ? sum / n : 0.0;
  auto variance = [&] {
    double v = 0.0;
    for (double e : x) v += (e - mean) * (e - mean);
    return n > 0 ? v / n : 0.0;  // population variance (§10.2)
  };
  if (f == "NUM") {
    result = n;
  } else if (x.empty()) {
    r.fail(c, "no rows to evaluate (all masked out)");
  } else if (f == "MAX" || f == "MIN" || f == "LMAX" || f == "LMIN") {
    const auto it = f == "MAX" || f == "LMAX" ? std::max_element(x.begin(), x.end())
                                              : std::min_element(x.begin(), x.end());
    result =
        f[0] == 'L' ? static_cast<double>(index[static_cast<std::size_t>(it - x.begin())]) : *it;
  } else if (f == "FIRST" || f == "LAST") {
    result = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k)
      if (x[k] != 0.0) {
        result = static_cast<double>(index[k]);
        if (f == "FIRST") break;
      }
  } else if (f == "SUM") {
    result = sum;
  } else if (f == "MEAN") {
    result = mean;
  } else if (f == "MEDI") {
    std::vector<double> y = x;
    std::sort(y.begin(), y.end());
    const std::size_t m = y.size();
    result = m % 2 == 1 ? y[m / 2] : 0.5 * (y[m / 2 - 1] + y[m / 2]);
  } else if (f == "VARI") {
    result = variance();
  } else if (f == "STDV") {
    result = std::sqrt(variance());
  } else if (f == "RMS") {
    double q = 0.0;
    for (double e : x) q += e * e;
    result = std::sqrt(q / n);
  } else {
    r.fail(c, fmt::format("function '{}' is not supported (MAX MIN LMAX LMIN FIRST LAST SUM "
                          "MEDI MEAN VARI STDV RMS NUM)",
                          c.text(2)));
  }
  result *= s.factor_result;
  if (s.abs_result) result = std::fabs(result);
  if (c.blank(1)) r.fail(c, "result parameter missing");
  assign_parameter(r, c, c.text(1), result);
}

void cmd_vfact(DeckReader& r, const Command& c) {
  VectorSettings& s = r.scripting.vector_settings;
  s.factor_result = r.real(c, 1, 1.0);
  s.factor1 = r.real(c, 2, 1.0);
  s.factor2 = r.real(c, 3, 1.0);
  s.factor3 = r.real(c, 4, 1.0);
}

void cmd_vmask(DeckReader& r, const Command& c) {
  if (c.blank(1)) {
    r.scripting.vector_settings.mask.clear();
    return;
  }
  const ArrayPosition m = array_position(r, c, c.text(1));  // checked now
  if (m.param->is_character_array()) r.fail(c, "a mask must be a numeric array");
  r.scripting.vector_settings.mask = c.text(1);
}

void cmd_vlen(DeckReader& r, const Command& c) {
  const int n = r.integer(c, 1, 0);
  if (n < 0) r.fail(c, "NROW must not be negative");
  r.scripting.vector_settings.n_rows = n == 0 ? std::nullopt : std::optional<int>(n);
  const int inc = r.integer(c, 2, 1);
  if (inc < 1) r.fail(c, "NINC must be at least 1");
  r.scripting.vector_settings.row_increment = inc;
}

void cmd_vcum(DeckReader& r, const Command& c) {
  r.scripting.vector_settings.cumulate = r.integer(c, 1, 0) != 0;
}

void cmd_vabs(DeckReader& r, const Command& c) {
  VectorSettings& s = r.scripting.vector_settings;
  s.abs_result = r.integer(c, 1, 0) != 0;
  s.abs1 = r.integer(c, 2, 0) != 0;
  s.abs2 = r.integer(c, 3, 0) != 0;
  s.abs3 = r.integer(c, 4, 0) != 0;
}

void cmd_vcol(DeckReader& r, const Command& c) {
  auto cols = [&](int f) -> std::optional<int> {
    if (c.blank(f)) return std::nullopt;
    const int n = r.integer(c, f, 1);
    if (n < 1) r.fail(c, fmt::format("field {}: at least one column", f));
    return n;
  };
  r.scripting.vector_settings.n_cols1 = cols(1);
  r.scripting.vector_settings.n_cols2 = cols(2);
}

void cmd_vstat(DeckReader& r, const Command&) {
  const VectorSettings& s = r.scripting.vector_settings;
  r.output.print(" VECTOR OPERATION SETTINGS (apply to the next *V or *M command)");
  r.output.print(fmt::format("   *VFACT  FACTR={:.8G} FACT1={:.8G} FACT2={:.8G} FACT3={:.8G}",
                             s.factor_result, s.factor1, s.factor2, s.factor3));
  r.output.print(fmt::format("   *VABS   KABSR={} KABS1={} KABS2={} KABS3={}", int(s.abs_result),
                             int(s.abs1), int(s.abs2), int(s.abs3)));
  r.output.print(fmt::format("   *VCUM   KEY={}", int(s.cumulate)));
  r.output.print(
      fmt::format("   *VLEN   NROW={} NINC={}", s.n_rows ? *s.n_rows : 0, s.row_increment));
  r.output.print(fmt::format("   *VCOL   NCOL1={} NCOL2={}", s.n_cols1 ? *s.n_cols1 : 0,
                             s.n_cols2 ? *s.n_cols2 : 0));
  r.output.print(fmt::format("   *VMASK  {}", s.mask.empty() ? "none" : s.mask));
}

}  // namespace

void register_array_commands(std::vector<CommandSpec>& t) {
  t.push_back({"*VFILL", cmd_vfill, kAnywhere});
  t.push_back({"*VOPER", cmd_voper, kAnywhere});
  t.push_back({"*VFUN", cmd_vfun, kAnywhere});
  t.push_back({"*VSCFUN", cmd_vscfun, kAnywhere});
  t.push_back({"*VFACT", cmd_vfact, kAnywhere});
  t.push_back({"*VMASK", cmd_vmask, kAnywhere});
  t.push_back({"*VLEN", cmd_vlen, kAnywhere});
  t.push_back({"*VCUM", cmd_vcum, kAnywhere});
  t.push_back({"*VABS", cmd_vabs, kAnywhere});
  t.push_back({"*VCOL", cmd_vcol, kAnywhere});
  t.push_back({"*VSTAT", cmd_vstat, kAnywhere});
  register_matrix_commands(t);
}

}  // namespace impactfe::deck
