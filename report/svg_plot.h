/// @file
/// @brief A small SVG plot writer (no runtime dependency): linear and log10 axes with nice
/// ticks and grids, series with lines, markers and error bars, slope guide lines, labelled
/// points and a legend, in the Okabe–Ito colour-blind-safe palette.
///
/// Pure: a `Plot` in, the text of one `<svg>` element out (deterministic bytes, no locale).
/// Typical use (an Allan deviation plot):
/// @code
///   Plot p;
///   p.id = "adev-gyro-x";
///   p.title = "Gyro x: Allan deviation";
///   p.x = {"τ [s]", Scale::log10};
///   p.y = {"σ(τ) [rad/s]", Scale::log10};
///   p.series.push_back({.name = "OADEV", .x = tau, .y = adev, .y_low = lo, .y_high = hi,
///                       .marker = Marker::circle});
///   p.guides.push_back({-0.5, 1.0, n, "−1/2"});
///   std::string svg = render_svg(p);
/// @endcode
#pragma once

#include <string>

#include "report/plot.h"

namespace imunoise::report {

/// The SVG text of PLOT: one `<svg>` element with xmlns, width/height and viewBox and no XML
/// declaration, so it can be written as a .svg file or inlined in HTML. Coordinates have at
/// most 2 decimals; the same Plot always gives the same bytes; text is XML-escaped (and
/// invalid UTF-8 replaced by U+FFFD). Throws InputError for a malformed Plot (x/y or error-bar
/// lengths differ, bad fixed axis limits).
std::string render_svg(const Plot& plot);

}  // namespace imunoise::report
