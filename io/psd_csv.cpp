#include "io/psd_csv.h"

#include <algorithm>
#include <map>
#include <ostream>

#include "analysis/psd_model.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "common/sensor_kind.h"
#include "io/atomic_output.h"
#include "io/result_files.h"
#include "pipeline/recording.h"

namespace imunoise::io {

namespace {

std::string unit_suffix_of(const std::string& axis_name) {
  return std::string(psd_unit_suffix(sensor_kind_of_channel(axis_name).value_or(SensorKind::gyro)));
}

}  // namespace

PsdTable psd_table(const std::vector<pipeline::AxisAnalysis>& axes, double tau0_s) {
  std::map<double, std::size_t> rows;  // frequency → row; a bin an axis lacks stays empty
  for (const auto& a : axes) {
    for (double f : a.psd.frequency_hz) rows.emplace(f, 0);
  }
  PsdTable table;
  for (const auto& [f, unused] : rows) {
    (void)unused;
    table.frequency_hz.push_back(f);
  }
  for (const auto& a : axes) {
    PsdAxis axis;
    axis.name = a.model.name;
    axis.psd.frequency_hz = a.psd.frequency_hz;
    axis.psd.density = a.psd.density;
    axis.psd.dof = a.psd.dof;
    for (double f : a.psd.frequency_hz) {
      axis.model_density.push_back(analysis::model_psd_one_sided(a.fit.coefficients, f, tau0_s));
    }
    table.axes.push_back(std::move(axis));
  }
  return table;
}

void write_psd_csv(const std::string& path, const PsdTable& table) {
  AtomicOutputFile file(path);
  std::ostream& out = file.stream();
  out << "frequency_hz";
  for (const PsdAxis& a : table.axes) {
    const std::string& n = a.name;
    const std::string u = unit_suffix_of(n);
    out << "," << n << "_psd_" << u << "," << n << "_psd_dof," << n << "_model_psd_" << u;
  }
  out << "\n";
  for (double f : table.frequency_hz) {
    out << shortest_number_text(f);
    for (const PsdAxis& a : table.axes) {
      const auto& freq = a.psd.frequency_hz;
      const auto it = std::find(freq.begin(), freq.end(), f);
      if (it == freq.end()) {
        out << ",,,";
        continue;
      }
      const auto i = static_cast<std::size_t>(it - freq.begin());
      out << "," << shortest_number_text(a.psd.density[i]) << ","
          << shortest_number_text(a.psd.dof[i]) << "," << shortest_number_text(a.model_density[i]);
    }
    out << "\n";
  }
  file.commit();
}

PsdTable read_psd_csv(const std::string& path) {
  const NumericTable t = read_numeric_table(path);
  const std::string what = "a psd.csv";
  const std::size_t frequency = require_column(t, path, "frequency_hz", what);
  PsdTable table;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    require_cells(t, path, r, {frequency});
    table.frequency_hz.push_back(*t.rows[r][frequency]);
  }
  for (const char* axis_name : pipeline::kImuChannelNames) {
    const std::string n = axis_name;
    const std::string u = unit_suffix_of(n);
    const auto value = t.find(n + "_psd_" + u);
    if (!value) continue;  // an axis that was not analysed
    const std::size_t dof = require_column(t, path, n + "_psd_dof", what);
    const std::size_t model = require_column(t, path, n + "_model_psd_" + u, what);
    PsdAxis a;
    a.name = n;
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      const auto& row = t.rows[r];
      if (!row[*value]) continue;
      require_cells(t, path, r, {dof, model});
      a.psd.frequency_hz.push_back(table.frequency_hz[r]);
      a.psd.density.push_back(*row[*value]);
      a.psd.dof.push_back(*row[dof]);
      a.model_density.push_back(*row[model]);
    }
    table.axes.push_back(std::move(a));
  }
  if (table.axes.empty()) {
    throw InputError(located_message(path, 1, 0, "no <axis>_psd_ columns found"));
  }
  return table;
}

}  // namespace imunoise::io
