/// @file
/// @brief The verdict of a fitted model (see verdict.h).
#include "report/verdict.h"

#include <algorithm>
#include <cstddef>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "common/number_text.h"
#include "io/filter_export.h"
#include "models/datasheet_units.h"

namespace imunoise::report {

namespace {

std::vector<const models::AxisModel*> axes_of(const models::NoiseModel& model, SensorKind kind) {
  std::vector<const models::AxisModel*> out;
  for (const models::AxisModel& axis : model.axes)
    if (axis.kind == kind) out.push_back(&axis);
  return out;
}

/// "0.150 [0.15, 0.16]" (3 significant digits, the interval 2-3), "< 0.0021 NOT_IDENTIFIED" or
/// NOT_IDENTIFIED alone when there is no bound.
std::string cell_text(const models::Estimate& e, const models::DatasheetUnit& unit,
                      std::string_view not_identified) {
  const double f = unit.factor;
  if (e.identified) {
    return significant_number_text(e.value * f, 3) + " [" +
           significant_number_text(e.ci_low * f, 3) + ", " +
           significant_number_text(e.ci_high * f, 3) + "]";
  }
  if (e.ci_high > 0.0)
    return "< " + significant_number_text(e.ci_high * f, 2) + " " + std::string(not_identified);
  return std::string(not_identified);
}

std::string term_heading(NoiseTerm term, SensorKind kind, bool ascii) {
  const models::DatasheetUnit unit = models::datasheet_unit(term, kind);
  return std::string(term_symbol(term)) + " " + std::string(term_name(term)) + " [" +
         std::string(ascii ? unit.ascii : unit.unicode) + "]";
}

std::string joined(const std::vector<std::string>& parts, std::string_view separator = ", ") {
  std::string out;
  for (const std::string& p : parts) out.append(out.empty() ? "" : separator).append(p);
  return out;
}

bool is_term_note(const ExplainedFinding& f) {
  return f.kind == "term_zero" || f.kind == "term_dropped";
}

/// TEXT in lines of at most WIDTH bytes: the first after INDENT, the others after NEXT_INDENT
/// (default: INDENT).
void wrap(std::ostringstream& out, const std::string& text, std::string_view indent,
          std::string_view next_indent = {}, std::size_t width = 96) {
  if (next_indent.empty()) next_indent = indent;
  std::istringstream words(text);
  std::string word, line;
  std::string_view current = indent;
  while (words >> word) {
    if (!line.empty() && current.size() + line.size() + 1 + word.size() > width) {
      out << current << line << "\n";
      line.clear();
      current = next_indent;
    }
    line.append(line.empty() ? "" : " ").append(word);
  }
  if (!line.empty()) out << current << line << "\n";
}

/// "Kalibr" of "Kalibr (imu.yaml)": the consumer without its file.
std::string short_consumer(std::string_view consumer) {
  const std::size_t paren = consumer.find(" (");
  return std::string(consumer.substr(0, paren));
}

}  // namespace

Table verdict_matrix(const models::NoiseModel& model, SensorKind kind) {
  Table t;
  t.id = std::string("verdict-") + std::string(sensor_name(kind));
  const std::vector<const models::AxisModel*> axes = axes_of(model, kind);
  t.caption = std::string(sensor_name(kind)) + ": coefficients in datasheet units with their " +
              significant_number_text(100.0 * model.confidence, 3) +
              " % intervals ('< bound' = not identified, at most the bound)";
  t.header = {"term [unit]"};
  for (const models::AxisModel* axis : axes) t.header.push_back(axis->name);
  if (axes.empty()) return t;
  for (NoiseTerm term : kNoiseTerms) {
    const models::DatasheetUnit unit = models::datasheet_unit(term, kind);
    std::vector<std::string> row{term_heading(term, kind, false)};
    for (const models::AxisModel* axis : axes)
      row.push_back(cell_text(axis->terms[term], unit, "not identified"));
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::vector<std::string> identification_lines(const models::NoiseModel& model) {
  std::vector<std::string> out;
  for (const SensorKind kind : kSensorKinds) {
    const std::vector<const models::AxisModel*> axes = axes_of(model, kind);
    if (axes.empty()) continue;
    std::vector<std::string> all, some, none;
    for (NoiseTerm term : kNoiseTerms) {
      std::vector<std::string> on;
      for (const models::AxisModel* axis : axes)
        if (axis->terms[term].identified) on.push_back(axis->name);
      const std::string symbol = term_symbol(term);
      if (on.size() == axes.size()) {
        all.push_back(symbol);
      } else if (on.empty()) {
        none.push_back(symbol);
      } else {
        some.push_back(symbol + " (" + joined(on) + ")");
      }
    }
    std::string line = std::string(sensor_name(kind)) +
                       ": identified on every axis: " + (all.empty() ? "none" : joined(all));
    if (!some.empty()) line += "; on some axes: " + joined(some, "; ");
    line += "; not identified: " + (none.empty() ? std::string("none") : joined(none)) + ".";
    out.push_back(std::move(line));
  }
  return out;
}

std::vector<ExplainedFinding> verdict_findings(const models::NoiseModel& model,
                                               std::string_view model_path) {
  const std::vector<ExplainedFinding> all = explain_model_findings(model, model_path);
  std::vector<ExplainedFinding> out;
  // (sensor, term) → index in OUT of the grouped note, and the record length its remedy needs.
  std::map<std::pair<int, int>, std::pair<std::size_t, double>> term_groups;
  for (const ExplainedFinding& f : all) {
    const models::AxisModel* axis = model.find_axis(f.where);
    const std::optional<NoiseTerm> term = leading_term(f.text);
    if (is_term_note(f) && axis && term) {
      const auto key = std::make_pair(static_cast<int>(axis->kind), static_cast<int>(*term));
      const double needed = duration_to_show_term(*axis, *term, model.duration_s).value_or(0.0);
      const auto found = term_groups.find(key);
      if (found == term_groups.end()) {
        ExplainedFinding g = f;
        g.text = std::string(term_symbol(*term)) + " (" + std::string(term_name(*term)) +
                 ") not identified; fit note: " + f.text;
        term_groups[key] = {out.size(), needed};
        out.push_back(std::move(g));
        continue;
      }
      ExplainedFinding& g = out[found->second.first];
      g.where += ", " + f.where;
      if (f.kind != g.kind && g.cause.find(f.cause) == std::string::npos)
        g.cause += "; on other axes: " + f.cause;
      if (needed > found->second.second) {
        found->second.second = needed;
        g.remedy = "on " + f.where + " (the longest record of these axes): " + f.remedy;
      }
      continue;
    }
    const auto same = std::find_if(out.begin(), out.end(), [&](const ExplainedFinding& g) {
      return !is_term_note(g) && g.kind == f.kind && g.text == f.text && g.cause == f.cause &&
             g.remedy == f.remedy;
    });
    if (same != out.end()) {
      same->where += ", " + f.where;
    } else {
      out.push_back(f);
    }
  }
  return out;
}

std::vector<ExportGuideEntry> export_guide(std::string_view model_path) {
  std::vector<ExportGuideEntry> out;
  const std::string model(model_path);
  for (const io::ExportFormat format : io::all_export_formats()) {
    if (format == io::ExportFormat::native) continue;
    out.push_back({std::string(io::export_format_consumer(format)),
                   "imunoise export " + model + " --to " +
                       std::string(io::export_format_name(format)) + " -o " +
                       std::string(io::default_export_file_name(format))});
  }
  out.push_back({"a filter with white-noise and random-walk bias states only (most of the above)",
                 "add --conservative: upper interval ends, B, Q and R folded into N and K"});
  out.push_back({"your own Kalman filter (Φ and Q_d of the sensor or 15-state INS error model)",
                 "imunoise discretize " + model + " --dt STEP_S --states 15 -o discrete"});
  return out;
}

Table export_guide_table(std::string_view model_path) {
  Table t;
  t.id = "export-guide";
  t.caption = "Which export for which filter (docs/exports.md: keys, units, conversions)";
  t.header = {"filter or framework", "command"};
  for (const ExportGuideEntry& e : export_guide(model_path))
    t.rows.push_back({e.consumer, e.command});
  return t;
}

std::string verdict_text(const models::NoiseModel& model, std::string_view model_path) {
  std::ostringstream out;
  out << "verdict\n";
  for (const SensorKind kind : kSensorKinds) {
    const std::vector<const models::AxisModel*> axes = axes_of(model, kind);
    if (axes.empty()) continue;
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> header{std::string(sensor_name(kind))};
    for (const models::AxisModel* axis : axes) header.push_back(axis->name);
    rows.push_back(header);
    for (NoiseTerm term : kNoiseTerms) {
      const models::DatasheetUnit unit = models::datasheet_unit(term, kind);
      std::vector<std::string> row{std::string(term_symbol(term)) + " [" + std::string(unit.ascii) +
                                   "]"};
      for (const models::AxisModel* axis : axes)
        row.push_back(cell_text(axis->terms[term], unit, "(n.i.)"));
      rows.push_back(std::move(row));
    }
    std::vector<std::size_t> width(header.size(), 0);
    for (const auto& row : rows)
      for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
    for (const auto& row : rows) {
      std::string line = "  ";
      for (std::size_t c = 0; c < row.size(); ++c) {
        line += row[c];
        if (c + 1 < row.size()) line += std::string(width[c] - row[c].size() + 2, ' ');
      }
      out << line << "\n";
    }
  }
  out << "  (values with their " << significant_number_text(100.0 * model.confidence, 3)
      << " % intervals in datasheet units; '< b (n.i.)' = not identified, at most b)\n";
  for (const std::string& line : identification_lines(model)) wrap(out, line, "  ", "    ");
  const std::vector<ExplainedFinding> findings = verdict_findings(model, model_path);
  out << "findings (" << findings.size() << "):" << (findings.empty() ? " none\n" : "\n");
  for (const ExplainedFinding& f : findings) {
    // The finding on one line, as written, so that it can be searched for.
    out << "  - " << f.where << ": " << f.text << "\n";
    wrap(out, "cause: " + f.cause, "      ");
    wrap(out, "remedy: " + f.remedy, "      ");
  }
  out << "export for your filter: imunoise export " << model_path
      << " --to FORMAT -o FILE, with FORMAT for:\n";
  std::vector<std::string> names;
  for (const io::ExportFormat format : io::all_export_formats())
    if (format != io::ExportFormat::native)
      names.push_back(short_consumer(io::export_format_consumer(format)) + " → " +
                      std::string(io::export_format_name(format)));
  wrap(out, joined(names, "; "), "  ");
  wrap(out,
       "white-noise + random-walk-bias filters: add --conservative; your own filter: imunoise "
       "discretize " +
           std::string(model_path) + " --dt STEP_S",
       "  ");
  return out.str();
}

}  // namespace imunoise::report
