/// @file
/// @brief The self-contained HTML report page (see html_page.h).
#include "report/html_page.h"

#include "common/errors.h"
#include "report/markup_text.h"

namespace imunoise::report {

namespace {

// Plain CSS, system fonts: the page must read well offline, printed, and in any browser.
constexpr std::string_view kStyle = R"(
body{font-family:"DejaVu Sans",Helvetica,Arial,sans-serif;color:#222;max-width:1180px;margin:1.5em auto;padding:0 1em;line-height:1.4}
h1{font-size:1.6em;margin-bottom:.2em}h2{font-size:1.25em;border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
dl.facts{display:grid;grid-template-columns:max-content minmax(0,1fr);gap:.15em 1em;margin:.8em 0}
dl.facts dt{font-weight:bold}dl.facts dd{margin:0;overflow-wrap:anywhere}
p,li{overflow-wrap:anywhere}
table{border-collapse:collapse;margin:.8em 0;font-size:.9em}
caption{text-align:left;font-weight:bold;padding:.3em 0}
th,td{border:1px solid #ccc;padding:.25em .5em;text-align:left;vertical-align:top}
th{background:#f2f2f2}tbody tr:nth-child(even){background:#fafafa}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
figure{margin:1.2em 0;page-break-inside:avoid}
figure svg{max-width:100%;height:auto;display:block}
figcaption{font-size:.9em;color:#444;max-width:900px}
pre{background:#f6f6f6;border:1px solid #ddd;padding:.6em;white-space:pre-wrap;overflow-wrap:anywhere;font-size:.85em}
footer{margin-top:3em;font-size:.8em;color:#666}
div.wide{overflow-x:auto;max-width:100%}
details{margin:.8em 0}details>summary{cursor:pointer;font-weight:bold;padding:.3em 0}
ul.findings{padding-left:1.2em}ul.findings li{margin:.5em 0}
ul.findings .cause,ul.findings .remedy{display:block;margin-left:.5em}
ul.findings .remedy{color:#064}
#verdict{border:2px solid #888;border-radius:6px;padding:0 1em .6em;margin-top:1em}
@media (max-width:640px){body{margin:.5em auto;padding:0 .5em}table{font-size:.8em}
th,td{padding:.2em .3em}td.num{white-space:normal}h1{font-size:1.3em}#verdict{padding:0 .5em .5em}}
)";

std::string escaped(std::string_view text) {
  std::string out;
  append_markup_text(out, text);
  return out;
}

/// A cell that holds a number, an interval "[a, b]" or a bound "< b" is right-aligned and kept
/// on one line.
bool looks_numeric(std::string cell) {
  if (cell.rfind("[", 0) == 0 || cell.rfind("< ", 0) == 0) cell.erase(0, cell[0] == '[' ? 1 : 2);
  if (cell.empty()) return false;
  const char c = cell.front();
  return (c >= '0' && c <= '9') ||
         ((c == '-' || c == '+') && cell.size() > 1 && cell[1] >= '0' && cell[1] <= '9');
}

void append_table(std::string& out, const Table& table) {
  if (table.folded) {
    out.append("<details><summary>")
        .append(escaped(table.caption.empty() ? table.id : table.caption))
        .append("</summary>\n");
  }
  out.append("<div class=\"wide\"><table");
  if (!table.id.empty()) out.append(" id=\"").append(escaped(table.id)).append("\"");
  out.append(">\n");
  if (!table.caption.empty())
    out.append("<caption>").append(escaped(table.caption)).append("</caption>\n");
  out.append("<thead><tr>");
  for (const std::string& h : table.header) out.append("<th>").append(escaped(h)).append("</th>");
  out.append("</tr></thead>\n<tbody>\n");
  for (const auto& row : table.rows) {
    IMUNOISE_EXPECT(row.size() == table.header.size(),
                    "report table '" + table.id + "': a row has " + std::to_string(row.size()) +
                        " cells, the header " + std::to_string(table.header.size()));
    out.append("<tr>");
    for (const std::string& cell : row) {
      out.append(looks_numeric(cell) ? "<td class=\"num\">" : "<td>");
      out.append(escaped(cell)).append("</td>");
    }
    out.append("</tr>\n");
  }
  out.append("</tbody></table></div>\n");
  if (table.folded) out.append("</details>\n");
}

void append_findings(std::string& out, const std::vector<FindingItem>& findings) {
  out.append("<ul class=\"findings\">\n");
  for (const FindingItem& f : findings) {
    out.append("<li><strong>").append(escaped(f.where)).append("</strong>: ");
    out.append(escaped(f.text));
    out.append("<span class=\"cause\">Cause: ").append(escaped(f.cause)).append("</span>");
    out.append("<span class=\"remedy\">Remedy: ").append(escaped(f.remedy)).append("</span>");
    out.append("</li>\n");
  }
  out.append("</ul>\n");
}

void append_figure(std::string& out, const FigureBlock& figure) {
  out.append("<figure id=\"fig-").append(escaped(figure.name)).append("\">\n");
  out.append(figure.svg);
  if (!figure.svg.empty() && figure.svg.back() != '\n') out.push_back('\n');
  out.append("<figcaption>").append(escaped(figure.caption));
  if (!figure.links.empty()) {
    out.append(" ");
    for (std::size_t i = 0; i < figure.links.size(); ++i) {
      out.append(i == 0 ? "[" : " · ");
      out.append("<a href=\"").append(escaped(figure.links[i].second)).append("\">");
      out.append(escaped(figure.links[i].first)).append("</a>");
    }
    out.append("]");
  }
  out.append("</figcaption>\n</figure>\n");
}

}  // namespace

std::string html_escape(std::string_view text) { return escaped(text); }

std::string render_html(const ReportPage& page) {
  std::string out;
  out.reserve(1 << 16);
  out.append("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
  out.append("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n");
  out.append("<title>").append(escaped(page.title)).append("</title>\n");
  out.append("<style>").append(kStyle).append("</style>\n</head>\n<body>\n");
  out.append("<header>\n<h1>").append(escaped(page.title)).append("</h1>\n");
  if (!page.facts.empty()) {
    out.append("<dl class=\"facts\">\n");
    for (const auto& [label, value] : page.facts) {
      out.append("<dt>").append(escaped(label)).append("</dt><dd>").append(escaped(value));
      out.append("</dd>\n");
    }
    out.append("</dl>\n");
  }
  out.append("</header>\n<main>\n");
  for (const PageSection& section : page.sections) {
    out.append("<section");
    if (!section.id.empty()) out.append(" id=\"").append(escaped(section.id)).append("\"");
    out.append(">\n<h2>").append(escaped(section.heading)).append("</h2>\n");
    for (const std::string& p : section.paragraphs) {
      out.append("<p>").append(escaped(p)).append("</p>\n");
    }
    // Open tables, then the findings, then the folded (detail) tables.
    for (const Table& t : section.tables)
      if (!t.folded) append_table(out, t);
    if (!section.findings.empty()) append_findings(out, section.findings);
    for (const Table& t : section.tables)
      if (t.folded) append_table(out, t);
    for (const FigureBlock& f : section.figures) append_figure(out, f);
    if (!section.bullets.empty()) {
      out.append("<ul>\n");
      for (const std::string& b : section.bullets) {
        out.append("<li>").append(escaped(b)).append("</li>\n");
      }
      out.append("</ul>\n");
    }
    if (!section.code_lines.empty()) {
      out.append("<pre><code>");
      for (const std::string& line : section.code_lines) out.append(escaped(line)).append("\n");
      out.append("</code></pre>\n");
    }
    out.append("</section>\n");
  }
  out.append("</main>\n");
  if (!page.footer.empty())
    out.append("<footer>").append(escaped(page.footer)).append("</footer>\n");
  out.append("</body>\n</html>\n");
  return out;
}

}  // namespace imunoise::report
