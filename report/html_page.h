/// @file
/// @brief A self-contained HTML report page (inline SVG and CSS, no script, no external
/// resource): a title, key facts, then sections of paragraphs, tables, figures, bullet lists and
/// command lines. Pure: a ReportPage in, the text of one HTML document out. All text is
/// escaped; figure SVG (from render_svg) is inlined as it is.
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

/// One section: `<section id="ID"><h2>HEADING</h2>…` with its parts in this order.
struct PageSection {
  std::string id;
  std::string heading;
  std::vector<std::string> paragraphs;
  std::vector<Table> tables;
  std::vector<FigureBlock> figures;
  std::vector<std::string> bullets;
  std::vector<std::string> code_lines;  ///< shown as one preformatted block (e.g. commands)
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
