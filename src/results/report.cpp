// `impactfe report`: fills the page template (compiled in, report_assets.h) with the style, the
// data of the run and the script bundle.
#include "results/report.h"

#include <fmt/format.h>

#include <fstream>

#include "core/errors.h"
#include "results/report_assets.h"
#include "results/svg_plot.h"

namespace impactfe {

namespace {

/// Replaces every occurrence of `placeholder` (none is a build error of the assets). Contents
/// are inserted in the order STYLE, DATA, SCRIPT and cannot contain a later placeholder.
void fill(std::string& page, const std::string& placeholder, const std::string& content) {
  auto at = page.find(placeholder);
  if (at == std::string::npos)
    throw std::logic_error("report template has no placeholder " + placeholder);
  for (; at != std::string::npos; at = page.find(placeholder, at + content.size()))
    page.replace(at, placeholder.size(), content);
}

}  // namespace

std::string report_html(const ResultsReader& reader, const ReportOptions& options) {
  std::string data = report_data_json(reader, options);
  // Inside <script type="application/json"> the text must not contain "</script" or "<!--":
  // '<' only occurs inside JSON strings, where \u003c is the same character.
  std::string safe;
  safe.reserve(data.size());
  for (char c : data) {
    if (c == '<')
      safe += "\\u003c";
    else
      safe += c;
  }
  std::string page(report_assets::kTemplate);
  const std::string title = reader.title().empty() ? reader.path() : reader.title();
  fill(page, "<!--IMPACTFE:TITLE-->", xml_escape(title));
  fill(page, "<!--IMPACTFE:STYLE-->", std::string(report_assets::kStyle));
  fill(page, "<!--IMPACTFE:DATA-->", safe);
  fill(page, "<!--IMPACTFE:SCRIPT-->", std::string(report_assets::kScript));
  return page;
}

std::uintmax_t write_report(const ResultsReader& reader, const ReportOptions& options,
                            const std::string& path) {
  const std::string page = report_html(reader, options);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(fmt::format("cannot write report '{}'", path));
  out << page;
  out.close();
  if (!out) throw InputError(fmt::format("cannot write report '{}'", path));
  return page.size();
}

}  // namespace impactfe
