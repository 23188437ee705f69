// Matrix commands *MFUN, *MOPER, the Fourier series *MFOURI and the array I/O commands *VGET,
// *VPUT (APDL_MODELING §10.1, §10.2). *VGET / *VPUT read and store through the *GET item
// providers of get_hooks.h.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "deck/vector_support.h"

namespace impactfe::deck {

GetItem read_get_item(DeckReader& r, const Command& c, int f) {
  GetItem q;
  q.entity = r.label(c, f);
  if (q.entity.empty()) r.fail(c, fmt::format("field {}: Entity missing", f));
  const std::string& ent = c.text(f + 1);
  if (ent.empty()) {
    q.entnum = 0.0;
  } else if (auto v = parse_fortran_number(ent)) {
    q.entnum = *v;
  } else if (q.entity == "PARM") {
    q.entname = to_upper(ent);
  } else {
    try {
      const Value v = r.evaluate_expression(ent);
      if (is_text(v))
        q.entname = to_upper(std::get<std::string>(v));
      else
        q.entnum = std::get<double>(v);
    } catch (const ExpressionError&) {
      q.entname = r.label(c, f + 1);  // a name: a component, ...
    }
  }
  q.item1 = r.label(c, f + 2);
  q.it1num = r.label(c, f + 3);
  q.item2 = r.label(c, f + 4);
  q.it2num = r.label(c, f + 5);
  return q;
}

namespace {

/// Highest entity number, for a *VGET result array created on the fly (§10.1 [A]).
long long highest_entity(const DeckReader& r, const std::string& entity) {
  if (entity == "NODE") return r.model.nodes.empty() ? 0 : r.model.nodes.rbegin()->first;
  if (entity == "ELEM") return r.model.elements.empty() ? 0 : r.model.elements.rbegin()->first;
  return 0;
}

/// The item of pass row k: KLOOP 0/2 advances ENTNUM, 4 IT1NUM, 6 IT2NUM.
GetItem item_of_row(DeckReader& r, const Command& c, const GetItem& q, int kloop, long long row) {
  GetItem k = q;
  switch (kloop) {
    case 0:
    case 1:
    case 2:
      k.entnum = q.entnum + static_cast<double>(row);
      break;
    case 4:
      k.it1num =
          format_number(r.eval(c, q.it1num.empty() ? "0" : q.it1num) + static_cast<double>(row));
      break;
    case 6:
      k.it2num =
          format_number(r.eval(c, q.it2num.empty() ? "0" : q.it2num) + static_cast<double>(row));
      break;
    default:
      r.fail(c, fmt::format("KLOOP {} is not supported (0 or 2: ENTNUM, 4: IT1NUM, 6: IT2NUM)",
                            kloop));
  }
  return k;
}

void cmd_vget(DeckReader& r, const Command& c) {
  // *VGET,ParR,Entity,ENTNUM,Item1,IT1NUM,Item2,IT2NUM,KLOOP
  GetItem q = read_get_item(r, c, 2);
  q.missing_is_zero = true;  // the loop runs whether or not the entity exists (§10.1)
  const int kloop = r.integer(c, 8, 0);
  const long long top = highest_entity(r, q.entity);
  const long long rows = kloop <= 2 && top > 0 ? top - static_cast<long long>(q.entnum) + 1 : 0;
  VectorPass p = begin_vector_pass(r, c, 1, rows);
  for (long long k = 0; k < p.rows; ++k) {
    if (!p.active[static_cast<std::size_t>(k)]) continue;
    const Value v = get_item(r, c, item_of_row(r, c, q, kloop, p.row(k)));
    if (is_text(v))
      r.fail(c,
             fmt::format("the item is a text ('{}'); ParR is numeric", std::get<std::string>(v)));
    p.store(k, std::get<double>(v));
  }
}

void cmd_vput(DeckReader& r, const Command& c) {
  // *VPUT,ParR,Entity,ENTNUM,Item1,IT1NUM,Item2,IT2NUM,KLOOP: ParR's column into the items.
  const GetItem q = read_get_item(r, c, 2);
  const int kloop = r.integer(c, 8, 0);
  VectorSettings s = r.scripting.vector_settings;
  r.scripting.vector_settings = VectorSettings{};
  const ArrayPosition pos = array_position(r, c, c.text(1));
  const long long avail = pos.param->imax - pos.i + 1;
  const long long rows = s.n_rows ? *s.n_rows : avail;
  const std::vector<double> values =
      read_vector(r, c, c.text(1), static_cast<int>(std::min(rows, avail)));
  for (long long k = 0; k < static_cast<long long>(values.size()); ++k)
    put_item(r, c, item_of_row(r, c, q, kloop, k), s.factor1 * values[static_cast<std::size_t>(k)]);
}

/// The matrix from the start element of field f: rows to the end of the column, columns to the
/// end of the row (or `cols`).
Eigen::MatrixXd read_matrix(DeckReader& r, const Command& c, int f, std::optional<int> cols,
                            const char* what) {
  if (c.blank(f)) r.fail(c, fmt::format("field {}: {} missing", f, what));
  const ArrayPosition pos = array_position(r, c, c.text(f));
  const Param& p = *pos.param;
  if (p.is_character_array()) r.fail(c, fmt::format("{} is a CHAR array", pos.name));
  const int m = p.imax - pos.i + 1;
  const int n = cols ? *cols : p.jmax - pos.j + 1;
  if (pos.j + n - 1 > p.jmax)
    r.fail(c,
           fmt::format("{} has {} columns, {} needed from column {}", pos.name, p.jmax, n, pos.j));
  Eigen::MatrixXd a(m, n);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = p.values[p.offset(pos.i + i, pos.j + j, pos.k)];
  return a;
}

/// Stores `a` from the start element of field f; the array is created when undefined.
void write_matrix(DeckReader& r, const Command& c, int f, const Eigen::MatrixXd& a) {
  const std::string& text = c.text(f);
  if (text.empty()) r.fail(c, fmt::format("field {}: result parameter missing", f));
  const auto n = split_subscripted_name(text);
  if (!n) r.fail(c, fmt::format("'{}' is not an array name or element", text));
  if (r.params.find(n->name) == nullptr) {
    int start[2] = {1, 1};
    for (std::size_t k = 0; k < n->subscripts.size() && k < 2; ++k)
      start[k] = static_cast<int>(std::lround(r.eval(c, n->subscripts[k])));
    r.params.define(n->name,
                    Param::array(ParamType::Array, start[0] - 1 + static_cast<int>(a.rows()),
                                 start[1] - 1 + static_cast<int>(a.cols()), 1));
  }
  const ArrayPosition pos = array_position(r, c, text);
  Param& p = *pos.param;
  if (p.is_character_array()) r.fail(c, fmt::format("{} is a CHAR array", pos.name));
  if (pos.i + a.rows() - 1 > p.imax || pos.j + a.cols() - 1 > p.jmax)
    r.fail(c, fmt::format("{} ({}x{}) cannot hold a {}x{} result from {}", pos.name, p.imax, p.jmax,
                          a.rows(), a.cols(), text));
  for (int i = 0; i < a.rows(); ++i)
    for (int j = 0; j < a.cols(); ++j) p.values[p.offset(pos.i + i, pos.j + j, pos.k)] = a(i, j);
}

void cmd_mfun(DeckReader& r, const Command& c) {
  // *MFUN,ParR,Func,Par1: COPY or TRAN(spose).
  const VectorSettings s = r.scripting.vector_settings;
  r.scripting.vector_settings = VectorSettings{};
  const std::string f = r.label(c, 2);
  const Eigen::MatrixXd a = read_matrix(r, c, 3, s.n_cols1, "Par1");
  if (f == "COPY")
    write_matrix(r, c, 1, a);
  else if (f == "TRAN")
    write_matrix(r, c, 1, a.transpose());
  else
    r.fail(c, fmt::format("function '{}' is not supported (COPY, TRAN)", c.text(2)));
}

void cmd_moper(DeckReader& r, const Command& c) {
  // *MOPER,ParR,Par1,Oper,Val1,...: MULT (Par1·Val1), INVERT, SOLV (Par1 x = Val1), COVAR, CORR.
  const VectorSettings s = r.scripting.vector_settings;
  r.scripting.vector_settings = VectorSettings{};
  const std::string op = r.label(c, 3);
  const Eigen::MatrixXd a = read_matrix(r, c, 2, s.n_cols1, "Par1");
  if (op == "MULT") {
    const Eigen::MatrixXd b = read_matrix(r, c, 4, s.n_cols2, "Par2 (Val1)");
    if (b.rows() < a.cols())
      r.fail(c,
             fmt::format("Par1 is {}x{} but Par2 has only {} rows", a.rows(), a.cols(), b.rows()));
    write_matrix(r, c, 1, a * b.topRows(a.cols()));
  } else if (op == "INVERT" || op == "SOLV") {
    if (a.rows() < a.cols())
      r.fail(c, fmt::format("Par1 ({}x{}) is not square", a.rows(), a.cols()));
    const Eigen::MatrixXd sq = a.topRows(a.cols());
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(sq);
    if (!lu.isInvertible()) r.fail(c, "Par1 is singular");
    if (op == "INVERT") {
      write_matrix(r, c, 1, lu.inverse());
    } else {
      const Eigen::MatrixXd b = read_matrix(r, c, 4, s.n_cols2, "Par2 (Val1)");
      if (b.rows() < sq.rows()) r.fail(c, "Par2 has fewer rows than Par1");
      write_matrix(r, c, 1, lu.solve(b.topRows(sq.rows())));
    }
  } else if (op == "COVAR" || op == "CORR") {
    // Columns of Par1 are variables, rows observations; population covariance (as *VSCFUN VARI).
    const Eigen::MatrixXd centred = a.rowwise() - a.colwise().mean();
    Eigen::MatrixXd cov = centred.transpose() * centred / static_cast<double>(a.rows());
    if (op == "CORR") {
      const Eigen::VectorXd d = cov.diagonal().cwiseSqrt();
      for (int i = 0; i < cov.rows(); ++i)
        for (int j = 0; j < cov.cols(); ++j)
          cov(i, j) = d(i) > 0.0 && d(j) > 0.0 ? cov(i, j) / (d(i) * d(j)) : 0.0;
    }
    write_matrix(r, c, 1, cov);
  } else {
    r.fail(c, fmt::format("operation '{}' is not supported (MULT, INVERT, SOLV, COVAR, CORR)",
                          c.text(3)));
  }
}

/// An array column of *MFOURI (field f) from its start element to the end of the column.
VectorOperand fourier_column(DeckReader& r, const Command& c, int f, const char* what) {
  const VectorOperand op = vector_operand(r, c, f);
  if (!op.column)
    r.fail(c, fmt::format("field {}: {} must be an array parameter ('{}')", f, what, c.text(f)));
  return op;
}

void cmd_mfouri(DeckReader& r, const Command& c) {
  // *MFOURI,Oper,COEFF,MODE,ISYM,THETA,CURVE (MAPDL Theory Reference, "Fourier Coefficient
  // Evaluation"): CURVE(θ) = Σj COEFF(j) F(MODE(j) θ), F = cos for ISYM 0 or 1, sin for -1, θ in
  // degrees. FIT finds COEFF by least squares over the points (θi, CURVEi); EVAL writes CURVE.
  const std::string oper = r.label(c, 1);
  if (oper != "FIT" && oper != "EVAL") r.fail(c, fmt::format("Oper '{}': FIT or EVAL", c.text(1)));
  const VectorOperand coeff = fourier_column(r, c, 2, "COEFF");
  const VectorOperand mode = fourier_column(r, c, 3, "MODE");
  const VectorOperand isym = fourier_column(r, c, 4, "ISYM");
  const VectorOperand theta = fourier_column(r, c, 5, "THETA");
  const VectorOperand curve = fourier_column(r, c, 6, "CURVE");
  const long long terms = mode.length();
  if (coeff.length() != terms || isym.length() != terms)
    r.fail(c, fmt::format("COEFF, MODE and ISYM must have the same length ({}, {}, {})",
                          coeff.length(), terms, isym.length()));
  const long long points = theta.length();
  if (curve.length() < points)
    r.fail(c, fmt::format("CURVE has {} values for {} THETA values", curve.length(), points));
  Eigen::MatrixXd g(points, terms);  // the sines and cosines at the points
  for (long long j = 0; j < terms; ++j) {
    const double key = isym.at(j);
    if (key != 0.0 && key != 1.0 && key != -1.0)
      r.fail(c, fmt::format("ISYM({}) = {}: 0 or 1 (cosine) or -1 (sine)", j + 1, key));
    for (long long i = 0; i < points; ++i) {
      const double a = mode.at(j) * theta.at(i) * std::numbers::pi / 180.0;
      g(i, j) = key == -1.0 ? std::sin(a) : std::cos(a);
    }
  }
  Param& out = *(oper == "FIT" ? coeff : curve).pos.param;
  const ArrayPosition& at = (oper == "FIT" ? coeff : curve).pos;
  if (oper == "EVAL") {
    Eigen::VectorXd a(terms);
    for (long long j = 0; j < terms; ++j) a(j) = coeff.at(j);
    const Eigen::VectorXd y = g * a;
    for (long long i = 0; i < points; ++i)
      out.values[out.offset(at.i + static_cast<int>(i), at.j, at.k)] = y(i);
    return;
  }
  if (points < terms)
    r.fail(c, fmt::format("FIT needs at least as many points ({}) as terms ({})", points, terms));
  Eigen::VectorXd y(points);
  for (long long i = 0; i < points; ++i) y(i) = curve.at(i);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(g);
  if (qr.rank() < terms)
    r.fail(c, "the terms are not independent at these points (a mode twice, or sin of mode 0)");
  const Eigen::VectorXd a = qr.solve(y);
  for (long long j = 0; j < terms; ++j)
    out.values[out.offset(at.i + static_cast<int>(j), at.j, at.k)] = a(j);
}

}  // namespace

void register_matrix_commands(std::vector<CommandSpec>& t) {
  t.push_back({"*VGET", cmd_vget, kAnywhere});
  t.push_back({"*VPUT", cmd_vput, kAnywhere});
  t.push_back({"*MFUN", cmd_mfun, kAnywhere});
  t.push_back({"*MOPER", cmd_moper, kAnywhere});
  t.push_back({"*MFOURI", cmd_mfouri, kAnywhere});
}

}  // namespace impactfe::deck
