/// @file
/// @brief The look of the SVG plots (internal to report/svg_*): fonts, colours and the sizes
/// of ticks, markers and the legend, in px unless stated.
#pragma once

#include <string_view>

namespace imunoise::report::svg_detail {

/// @name Fonts
/// @{
inline constexpr std::string_view kFontFamily = "DejaVu Sans, Helvetica, Arial, sans-serif";
inline constexpr double kTickFont = 12.0;
inline constexpr double kExponentFont = 10.0;
inline constexpr double kLabelFont = 14.0;
inline constexpr double kTitleFont = 16.0;
inline constexpr double kSmallFont = 12.0;  ///< legend, guide and point labels
inline constexpr double kCharWidth = 0.6;   ///< mean advance of the sans-serif fonts [em]
/// @}

/// @name Colours
/// @{
inline constexpr std::string_view kTextColor = "#222222";
inline constexpr std::string_view kFrameColor = "#444444";
inline constexpr std::string_view kMajorGridColor = "#d2d2d2";
inline constexpr std::string_view kMinorGridColor = "#ececec";
inline constexpr std::string_view kGuideColor = "#8c8c8c";
inline constexpr std::string_view kGuideTextColor = "#555555";
/// @}

/// @name Sizes [px]
/// @{
inline constexpr double kMajorTick = 5.0, kMinorTick = 3.0;  ///< tick marks, outwards
inline constexpr double kMarkerRadius = 3.5;
inline constexpr double kPointRadius = 4.5;   ///< labelled points
inline constexpr double kCapHalfWidth = 3.0;  ///< error-bar caps
inline constexpr double kLegendRow = 18.0, kLegendSample = 30.0, kLegendPad = 8.0;
/// @}

}  // namespace imunoise::report::svg_detail
