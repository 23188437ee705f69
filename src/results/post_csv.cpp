#include "results/post_csv.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/errors.h"
#include "core/text.h"

namespace impactfe {

namespace {

std::string trim(const std::string& s) {
  auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split_fields(const std::string& spec) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    auto comma = spec.find(',', start);
    out.push_back(trim(spec.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

/// Strict positive integer: digits only, no sign, no trailing characters.
std::optional<int> parse_positive(const std::string& s) {
  if (s.empty() || s.size() > 9 ||
      !std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); }))
    return std::nullopt;
  int v = std::stoi(s);
  if (v <= 0) return std::nullopt;
  return v;
}

bool is_nodal_label(const std::string& lab) {
  static const char* labels[] = {"UX", "UY", "UZ", "ROTX", "ROTY", "ROTZ", "VX", "VY", "VZ",
                                 "AX", "AY", "AZ", "FX",   "FY",   "FZ",   "MX", "MY", "MZ"};
  return std::any_of(std::begin(labels), std::end(labels), [&](const char* l) { return lab == l; });
}

bool is_item_name(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(),
                                   [](unsigned char c) { return std::isalnum(c) || c == '_'; });
}

/// printf "%.10e"; empty for an absent (non-finite) value.
std::string number(double v) {
  if (!std::isfinite(v)) return {};
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10e", v);
  return buf;
}

}  // namespace

PostRequest parse_nsol(const std::string& spec) {
  auto f = split_fields(spec);
  if (f.size() != 2 || !parse_positive(f[0]))
    throw InputError(fmt::format("nodal request '{}': expected NODE,LAB (e.g. 2,UX)", spec));
  std::string lab = to_upper(f[1]);
  if (!is_nodal_label(lab))
    throw InputError(fmt::format(
        "nodal request '{}': unknown label '{}' (expected UX UY UZ ROTX ROTY ROTZ, VX VY VZ, "
        "AX AY AZ or FX FY FZ MX MY MZ)",
        spec, f[1]));
  return {PostRequest::Nodal, *parse_positive(f[0]), lab};
}

PostRequest parse_esol(const std::string& spec) {
  auto f = split_fields(spec);
  if (f.size() != 2 || !parse_positive(f[0]) || !is_item_name(f[1]))
    throw InputError(fmt::format("element request '{}': expected ELEM,ITEM (e.g. 6,SAXL)", spec));
  return {PostRequest::Element, *parse_positive(f[0]), to_upper(f[1])};
}

PostRequest parse_gapf(const std::string& spec) {
  auto f = split_fields(spec);
  if (f.size() != 1 || !parse_positive(f[0]))
    throw InputError(fmt::format("gap request '{}': expected the gap number NUM (e.g. 1)", spec));
  return {PostRequest::Gap, *parse_positive(f[0]), ""};
}

PostRequest parse_rcforc(const std::string& spec) {
  auto f = split_fields(spec);
  const std::string lab = f.size() == 2 ? to_upper(f[1]) : "";
  if (f.size() != 2 || !parse_positive(f[0]) || (lab != "FX" && lab != "FY" && lab != "FZ"))
    throw InputError(fmt::format(
        "contact force request '{}': expected the contact entity and FX, FY or FZ (e.g. 1,FZ)",
        spec));
  return {PostRequest::Contact, *parse_positive(f[0]), lab};
}

PostRequest parse_part_energy(const std::string& spec) {
  auto f = split_fields(spec);
  const std::string lab = f.size() == 2 ? to_upper(f[1]) : "";
  if (f.size() != 2 || !parse_positive(f[0]) || (lab != "KE" && lab != "IE" && lab != "HE"))
    throw InputError(
        fmt::format("part energy request '{}': expected the part and KE, IE or HE "
                    "(e.g. 1,KE)",
                    spec));
  return {PostRequest::Part, *parse_positive(f[0]), lab};
}

std::string post_column_name(const PostRequest& r) {
  switch (r.kind) {
    case PostRequest::Nodal:
      return fmt::format("N{}_{}", r.id, r.label);
    case PostRequest::Element:
      return fmt::format("E{}_{}", r.id, r.label);
    case PostRequest::Gap:
      return fmt::format("GAP{}", r.id);
    case PostRequest::Contact:
      return fmt::format("CONTACT{}_{}", r.id, r.label);
    case PostRequest::Part:
      return fmt::format("PART{}_{}", r.id, r.label);
  }
  return {};
}

std::vector<std::pair<double, double>> post_series(const ResultsReader& reader,
                                                   const PostRequest& r) {
  switch (r.kind) {
    case PostRequest::Nodal:
      return reader.nodal_series(r.id, r.label);
    case PostRequest::Element:
      return reader.element_series(r.id, r.label);
    case PostRequest::Gap:
      return reader.gap_force_series(r.id);
    case PostRequest::Contact:
      return reader.contact_force_series(r.id, r.label);
    case PostRequest::Part:
      return reader.part_energy_series(r.id, r.label);
  }
  return {};
}

std::string post_csv(const ResultsReader& reader, const std::vector<PostRequest>& requests) {
  std::vector<std::vector<std::pair<double, double>>> series;
  std::string out = "time";
  for (const auto& r : requests) {
    series.push_back(post_series(reader, r));
    // A quantity stored at no time point (OUTRES did not write it, or it was never computed)
    // is an error, not an empty column.
    if (series.back().empty())
      throw InputError(
          fmt::format("{}: no value is stored in '{}' (not written by OUTRES, or "
                      "not computed for this node / element)",
                      post_column_name(r), reader.path()));
    out += ',';
    out += post_column_name(r);
  }
  out += "\n";
  // k-way merge of the time-sorted series: each row takes the smallest pending time and
  // consumes one entry from every series whose next entry is at that time.
  std::vector<std::size_t> head(series.size(), 0);
  while (true) {
    double t = std::numeric_limits<double>::infinity();
    bool any = false;
    for (std::size_t c = 0; c < series.size(); ++c)
      if (head[c] < series[c].size()) {
        t = std::min(t, series[c][head[c]].first);
        any = true;
      }
    if (!any) break;
    std::string row = number(t);
    for (std::size_t c = 0; c < series.size(); ++c) {
      row += ",";
      if (head[c] < series[c].size() && same_time(series[c][head[c]].first, t))
        row += number(series[c][head[c]++].second);
    }
    out += row + "\n";
  }
  return out;
}

std::string frequencies_csv(const ResultsReader& reader) {
  std::string out = "mode,frequency_hz\n";
  auto f = reader.frequencies();
  for (std::size_t i = 0; i < f.size(); ++i) out += fmt::format("{},{}\n", i + 1, number(f[i]));
  return out;
}

std::string mode_shape_csv(const ResultsReader& reader, int mode) {
  Eigen::MatrixXd shape = reader.mode_shape(mode);
  std::string out = "node,UX,UY,UZ,ROTX,ROTY,ROTZ\n";
  const auto& ids = reader.node_ids();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    out += std::to_string(ids[i]);
    for (int j = 0; j < 6; ++j) {
      out += ',';
      out += number(shape(static_cast<Eigen::Index>(i), j));
    }
    out += "\n";
  }
  return out;
}

std::string results_info(const ResultsReader& reader) {
  std::string out = fmt::format("Results file: {}\n", reader.path());
  out += fmt::format("Title: {}\n", reader.title());
  if (!reader.units().empty()) out += fmt::format("Units: {} (/UNITS)\n", reader.units());
  out +=
      fmt::format("Nodes: {}\nElements: {}\n", reader.node_ids().size(), reader.elements().size());
  const auto analyses = reader.analyses();
  out += fmt::format("Analyses: {}\n", analyses.size());
  for (const auto& a : analyses) {
    out += fmt::format("Analysis {}: {}", a.index, results_kind_name(a.kind));
    if (!a.description.empty()) out += fmt::format(" ({})", a.description);
    out += fmt::format(", status: {}\n", a.status);
    out += fmt::format("  time points: {}", a.n_time_points);
    if (a.n_time_points > 0)
      out += fmt::format(", time {:.6g} .. {:.6g}", a.time_first, a.time_last);
    out += "\n";
    if (!a.element_families.empty()) {
      out += "  element families:";
      for (const auto& f : a.element_families) out += " " + f;
      out += "\n";
    }
    if (a.n_gaps > 0) out += fmt::format("  gap forces: {}\n", a.n_gaps);
    if (a.n_contacts > 0) out += fmt::format("  contact forces: {} contacts\n", a.n_contacts);
    if (a.n_parts > 0) out += fmt::format("  part energies: {} parts\n", a.n_parts);
    if (a.n_modes > 0) out += fmt::format("  modes: {}\n", a.n_modes);
    for (const auto& [name, value] : a.numeric_attributes)
      out += fmt::format("  {} = {:.10g}\n", name, value);
    for (const auto& [name, value] : a.text_attributes)
      out += fmt::format("  {} = {}\n", name, value);
  }
  return out;
}

}  // namespace impactfe
