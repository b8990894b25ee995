/// @file
/// @brief DIR/report.html and DIR/plots/ from the saved results of DIR (see write_report.h).
#include "report/write_report.h"

#include <chrono>
#include <ctime>
#include <filesystem>
#include <string>

#include "io/atomic_output.h"
#include "io/results_directory.h"
#include "report/fleet_page.h"
#include "report/html_page.h"
#include "report/report_page.h"

namespace imunoise::report {

namespace {

std::string utc_now_text() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M UTC", &tm);
  return buffer;
}

}  // namespace

ReportOutput write_report(const std::string& dir) {
  const ReportDocument doc = build_report_page(io::load_results_directory(dir), utc_now_text());
  const std::filesystem::path root(dir);
  const std::string html_path = (root / "report.html").string();
  const std::string html = render_html(doc.page);
  io::create_output_directory((root / "plots").string());
  for (const ReportFile& file : doc.plot_files) {
    io::write_file_atomically((root / file.relative_path).string(), file.text);
  }
  io::write_file_atomically(html_path, html);
  return {html_path, figure_count(doc.page)};
}

std::string write_fleet_report(const std::string& dir, const pipeline::FleetResult& result) {
  const std::string path = (std::filesystem::path(dir) / "fleet.html").string();
  io::write_file_atomically(path, render_html(build_fleet_page(result, utc_now_text())));
  return path;
}

}  // namespace imunoise::report
