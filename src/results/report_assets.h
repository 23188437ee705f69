#pragma once
/// The front end of `impactfe report`, compiled into the binary: generated at build time from
/// report/src/ (template.html, report.css, report.js bundled with uPlot and three.js from the npm
/// registry; report/build_assets.mjs) into <build>/generated/report_assets.cpp.
#include <string_view>

namespace impactfe::report_assets {

/// The page with the placeholders <!--IMPACTFE:TITLE-->, <!--IMPACTFE:STYLE-->,
/// <!--IMPACTFE:DATA--> and <!--IMPACTFE:SCRIPT-->.
extern const std::string_view kTemplate;
/// Style sheet (uPlot's and the page's).
extern const std::string_view kStyle;
/// Minified script bundle (IIFE): uPlot, three.js, OrbitControls and the page code.
extern const std::string_view kScript;
/// Versions of the bundled libraries, e.g. "uPlot 1.6.32, three.js 0.187.0".
extern const std::string_view kLibraries;

}  // namespace impactfe::report_assets
