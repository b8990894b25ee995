#include "io/allan_csv.h"

#include <cmath>
#include <map>
#include <ostream>

#include "analysis/noise_terms.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "common/sensor_kind.h"
#include "io/atomic_output.h"
#include "io/result_files.h"
#include "pipeline/recording.h"

namespace imunoise::io {

namespace {

std::string unit_suffix_of(const std::string& axis_name) {
  return std::string(
      rate_unit_suffix(sensor_kind_of_channel(axis_name).value_or(SensorKind::gyro)));
}

/// The point of CURVE at averaging factor M, or nullptr.
const analysis::DeviationPoint* point_at(const analysis::DeviationCurve& curve, std::int64_t m) {
  for (const auto& p : curve.points) {
    if (p.m == m) return &p;
  }
  return nullptr;
}

}  // namespace

AllanTable allan_table(const std::vector<pipeline::AxisAnalysis>& axes, double tau0_s) {
  std::map<std::int64_t, std::size_t> rows;
  for (const auto& a : axes) {
    for (const auto& p : a.oadev.points) rows.emplace(p.m, 0);
    for (const auto& p : a.ohdev.points) rows.emplace(p.m, 0);
  }
  AllanTable table;
  for (const auto& [m, unused] : rows) {
    (void)unused;
    table.m.push_back(m);
    table.tau_s.push_back(static_cast<double>(m) * tau0_s);
  }
  for (const auto& a : axes) {
    AllanAxis axis{a.model.name, a.oadev, a.ohdev, {}};
    for (double tau : table.tau_s) {
      axis.model_adev.push_back(std::sqrt(analysis::model_avar(a.fit.coefficients, tau)));
    }
    table.axes.push_back(std::move(axis));
  }
  return table;
}

void write_allan_csv(const std::string& path, const AllanTable& table) {
  AtomicOutputFile file(path);
  std::ostream& out = file.stream();
  out << "m,tau_s";
  for (const AllanAxis& a : table.axes) {
    const std::string& n = a.name;
    const std::string u = unit_suffix_of(n);
    out << "," << n << "_oadev_" << u << "," << n << "_oadev_ci_low_" << u << "," << n
        << "_oadev_ci_high_" << u << "," << n << "_oadev_edf," << n << "_oadev_alpha," << n
        << "_model_adev_" << u << "," << n << "_ohdev_" << u << "," << n << "_ohdev_ci_low_" << u
        << "," << n << "_ohdev_ci_high_" << u;
  }
  out << "\n";
  for (std::size_t r = 0; r < table.m.size(); ++r) {
    const std::int64_t m = table.m[r];
    out << m << "," << shortest_number_text(table.tau_s[r]);
    for (const AllanAxis& a : table.axes) {
      if (const auto* p = point_at(a.oadev, m)) {
        out << "," << shortest_number_text(p->value) << "," << shortest_number_text(p->ci_low)
            << "," << shortest_number_text(p->ci_high) << "," << shortest_number_text(p->edf) << ","
            << p->alpha;
      } else {
        out << ",,,,,";
      }
      out << "," << shortest_number_text(a.model_adev.at(r));
      if (const auto* p = point_at(a.ohdev, m)) {
        out << "," << shortest_number_text(p->value) << "," << shortest_number_text(p->ci_low)
            << "," << shortest_number_text(p->ci_high);
      } else {
        out << ",,,";
      }
    }
    out << "\n";
  }
  file.commit();
}

AllanTable read_allan_csv(const std::string& path, double confidence) {
  const NumericTable t = read_numeric_table(path);
  const std::string what = "an allan.csv";
  const std::size_t m_column = require_column(t, path, "m", what);
  const std::size_t tau_column = require_column(t, path, "tau_s", what);
  AllanTable table;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    require_cells(t, path, r, {m_column, tau_column});
    const double m = *t.rows[r][m_column];
    if (!(m >= 1.0 && m == std::floor(m) && m < 0x1p62)) {
      throw InputError(
          located_message(path, file_line_of_row(r), 0,
                          "m: expected an averaging factor >= 1, got " + shortest_number_text(m)));
    }
    table.m.push_back(static_cast<std::int64_t>(m));
    table.tau_s.push_back(*t.rows[r][tau_column]);
  }
  for (const char* axis_name : pipeline::kImuChannelNames) {
    const std::string u = unit_suffix_of(axis_name);
    const std::string n = axis_name;
    const auto oadev = t.find(n + "_oadev_" + u);
    if (!oadev) continue;  // an axis that was not analysed
    const auto column = [&](const std::string& name) {
      return require_column(t, path, name, what);
    };
    const std::size_t oadev_low = column(n + "_oadev_ci_low_" + u);
    const std::size_t oadev_high = column(n + "_oadev_ci_high_" + u);
    const std::size_t edf = column(n + "_oadev_edf");
    const std::size_t alpha = column(n + "_oadev_alpha");
    const std::size_t model = column(n + "_model_adev_" + u);
    const std::size_t ohdev = column(n + "_ohdev_" + u);
    const std::size_t ohdev_low = column(n + "_ohdev_ci_low_" + u);
    const std::size_t ohdev_high = column(n + "_ohdev_ci_high_" + u);
    AllanAxis a;
    a.name = n;
    a.oadev.type = analysis::DeviationType::oadev;
    a.ohdev.type = analysis::DeviationType::ohdev;
    for (analysis::DeviationCurve* c : {&a.oadev, &a.ohdev}) {
      c->confidence = confidence;
      if (!table.m.empty()) c->tau0_s = table.tau_s.front() / static_cast<double>(table.m.front());
    }
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      const auto& row = t.rows[r];
      require_cells(t, path, r, {model});
      a.model_adev.push_back(*row[model]);
      if (row[*oadev]) {
        require_cells(t, path, r, {oadev_low, oadev_high, edf, alpha});
        analysis::DeviationPoint p;
        p.m = table.m[r];
        p.tau_s = table.tau_s[r];
        p.value = *row[*oadev];
        p.ci_low = *row[oadev_low];
        p.ci_high = *row[oadev_high];
        p.edf = *row[edf];
        const double alpha_value = *row[alpha];
        if (alpha_value != std::round(alpha_value) || std::abs(alpha_value) > 4.0) {
          throw InputError(located_message(path, file_line_of_row(r), 0,
                                           "column '" + t.columns[alpha] +
                                               "': expected a noise type -4..4, got " +
                                               shortest_number_text(alpha_value)));
        }
        p.alpha = static_cast<int>(alpha_value);
        a.oadev.points.push_back(p);
      }
      if (row[ohdev]) {
        require_cells(t, path, r, {ohdev_low, ohdev_high});
        analysis::DeviationPoint p;
        p.m = table.m[r];
        p.tau_s = table.tau_s[r];
        p.value = *row[ohdev];
        p.ci_low = *row[ohdev_low];
        p.ci_high = *row[ohdev_high];
        a.ohdev.points.push_back(p);
      }
    }
    table.axes.push_back(std::move(a));
  }
  if (table.axes.empty()) {
    throw InputError(located_message(path, 1, 0, "no <axis>_oadev_/_ohdev_ columns found"));
  }
  return table;
}

}  // namespace imunoise::io
