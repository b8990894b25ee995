/// @file
/// @brief A self-contained HTML report page (inline SVG and CSS, no script, no external
/// resource): a title, key facts, then sections of paragraphs, findings with cause and remedy,
/// tables (each scrolling sideways on a narrow screen, detail tables folded in `<details>`),
/// figures, bullet lists and command lines. Pure: a ReportPage in, the text of one HTML document
/// out. All text is escaped; figure SVG (from render_svg) is inlined as it is.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace imunoise::report {

/// A table: header cells and rows of text cells (each row as long as the header).
struct Table {
  std::string id;  ///< HTML id ("" = none)
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  /// Folded: shown as `<details>` whose summary is the caption (a detail table, opened by a
  /// click, no script).
  bool folded = false;
};

/// A finding as the verdict lists it: where, what, why, and what to do.
struct FindingItem {
  std::string where;   ///< "recording", "gyro_x, gyro_y", …
  std::string text;    ///< the finding
  std::string cause;   ///< why it happens
  std::string remedy;  ///< the command or flag that addresses it
};

/// A figure as it appears on the page: `<figure id="fig-NAME">` with the SVG, the caption and
/// links to the files behind it (relative to the page).
struct FigureBlock {
  std::string name;
  std::string svg;  ///< one <svg> element (render_svg)
  std::string caption;
  std::vector<std::pair<std::string, std::string>>
      links;  ///< (text, href), e.g. ("data", "plots/x.csv")
};

/// One section: `<section id="ID"><h2>HEADING</h2>…` with its parts in this order (findings:
/// see below).
struct PageSection {
  std::string id;
  std::string heading;
  std::vector<std::string> paragraphs;
  std::vector<Table> tables;
  std::vector<FigureBlock> figures;
  std::vector<std::string> bullets;
  std::vector<std::string> code_lines;  ///< shown as one preformatted block (e.g. commands)
  /// `<ul class="findings">`, each item with its cause and remedy; shown after the open
  /// tables and before the folded ones.
  std::vector<FindingItem> findings = {};
};

struct ReportPage {
  std::string title;                                       ///< <title> and <h1>
  std::vector<std::pair<std::string, std::string>> facts;  ///< (label, value) under the title
  std::vector<PageSection> sections;
  std::string footer;
};

/// TEXT as HTML text or double-quoted attribute (see append_markup_text).
std::string html_escape(std::string_view text);

/// The HTML document of PAGE (UTF-8, `<!DOCTYPE html>`). Throws ContractViolation if a table
/// row's length differs from its header's.
std::string render_html(const ReportPage& page);

}  // namespace imunoise::report
