#include "io/recording_csv_writer.h"

#include <algorithm>
#include <charconv>
#include <ostream>
#include <vector>

#include "common/number_text.h"
#include "io/atomic_output.h"

namespace imunoise::io {

char* append_csv_row(char* out, double time_s, std::span<const double> values) {
  out = std::to_chars(out, out + 24, time_s).ptr;
  for (const double v : values) {
    *out++ = ',';
    out = std::to_chars(out, out + 24, v).ptr;
  }
  *out++ = '\n';
  return out;
}

std::string csv_column_name(const pipeline::Channel& channel) {
  if (!channel.kind) return channel.name;
  return channel.name + "_" + std::string(rate_unit_suffix(*channel.kind));
}

void write_recording_csv(const pipeline::Recording& rec, const std::string& path) {
  AtomicOutputFile file(path);
  std::ostream& out = file.stream();
  out << "# imunoise convert: " << rec.source_path << ", SI units\n"
      << "# sample_period_s: " << shortest_number_text(rec.sample_period_s) << "\n"
      << "# start_time_s: " << shortest_number_text(rec.start_time_s) << "\n"
      << "# samples: " << rec.sample_count() << "\n";
  if (rec.time_s.empty()) {
    out << "# time_s: k / " << shortest_number_text(rec.report.timing.rate_hz)
        << " Hz (the input had a fixed rate)\n";
  }
  for (const pipeline::Channel& c : rec.channels) {
    out << "# " << c.name << ": from " << c.source_column
        << (c.source_unit.empty() ? "" : " [" + c.source_unit + "]")
        << (c.from_increments ? " (increments divided by the sample period)" : "") << "\n";
  }
  out << "time_s";
  for (const pipeline::Channel& c : rec.channels) out << "," << csv_column_name(c);
  out << "\n";

  constexpr std::size_t kBlockRows = 4096;
  const std::size_t columns = rec.channels.size();
  std::vector<char> text(kBlockRows * (columns + 1) * kCsvFieldChars);
  std::vector<double> row(columns);
  const std::size_t n = rec.sample_count();
  for (std::size_t first = 0; first < n; first += kBlockRows) {
    const std::size_t last = std::min(n, first + kBlockRows);
    char* p = text.data();
    for (std::size_t i = first; i < last; ++i) {
      for (std::size_t c = 0; c < columns; ++c) row[c] = rec.channels[c].values[i];
      p = append_csv_row(p, pipeline::sample_time_s(rec, i), row);
    }
    out.write(text.data(), p - text.data());
  }
  file.commit();
}

}  // namespace imunoise::io
