#include "battery/scoring.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace imunoise::battery {

namespace {

const std::array<NoiseTerm, 5> kPowerLawTerms = {NoiseTerm::quantization, NoiseTerm::white_noise,
                                                 NoiseTerm::bias_instability,
                                                 NoiseTerm::random_walk, NoiseTerm::ramp};
const std::array<Coefficient, 5> kPowerLawCoefficients = {
    Coefficient::quantization, Coefficient::white_noise, Coefficient::bias_instability,
    Coefficient::random_walk, Coefficient::ramp};

double power_law_truth(const ChannelTruth& t, Coefficient c) {
  switch (c) {
    case Coefficient::quantization:
      return t.quantization;
    case Coefficient::white_noise:
      return t.white_noise;
    case Coefficient::bias_instability:
      return t.bias_instability;
    case Coefficient::random_walk:
      return t.random_walk;
    case Coefficient::ramp:
      return t.ramp;
    default:
      return 0.0;
  }
}

double record_length(const BatteryCase& c) {
  return static_cast<double>(c.spec.samples) / c.spec.rate_hz;
}

/// The GM upper bound of AXIS at TAU_C_S, interpolated linearly in (ln T_c, ln σ_max) between
/// its curve's points; none outside the curve's T_c range.
std::optional<double> gauss_markov_bound_at(const models::AxisModel& axis, double tau_c_s) {
  const std::vector<GaussMarkovBound>& curve = axis.gauss_markov_bounds;
  for (std::size_t j = 0; j + 1 < curve.size(); ++j) {
    const GaussMarkovBound& a = curve[j];
    const GaussMarkovBound& b = curve[j + 1];
    if (tau_c_s < a.tau_c_s || tau_c_s > b.tau_c_s) continue;
    if (!(a.sigma_max > 0.0 && b.sigma_max > 0.0)) return std::max(a.sigma_max, b.sigma_max);
    const double w = std::log(tau_c_s / a.tau_c_s) / std::log(b.tau_c_s / a.tau_c_s);
    return std::exp((1.0 - w) * std::log(a.sigma_max) + w * std::log(b.sigma_max));
  }
  return std::nullopt;
}

/// The rows of one channel; AXIS may be null (channel missing or analysis failed).
void score_channel(const BatteryCase& c, const ChannelTruth& t, const models::AxisModel* axis,
                   std::vector<ScoreRow>& rows, std::vector<ChannelExtras>& extras) {
  const double length = record_length(c);
  std::optional<bool> psd_pass = axis ? axis->psd_check_pass : std::nullopt;
  for (std::size_t i = 0; i < kPowerLawTerms.size(); ++i) {
    ScoreRow r;
    r.channel = t.name;
    r.term = kPowerLawCoefficients[i];
    r.truth = power_law_truth(t, r.term);
    r.truth_as_recorded = r.term == Coefficient::white_noise ? t.white_noise_as_recorded : r.truth;
    if (axis) {
      const models::Estimate& e = axis->terms[kPowerLawTerms[i]];
      r.estimate = e.value;
      r.ci_low = e.ci_low;
      r.ci_high = e.ci_high;
      r.has_interval = true;
      r.identified = e.identified;
      r.readoff = axis->readoff.slope[kPowerLawTerms[i]];
    }
    r.covered = r.truth > 0.0 && r.has_interval && r.ci_low <= r.truth && r.truth <= r.ci_high;
    if (r.term == Coefficient::random_walk) r.k_share_t10 = random_walk_share(t, length / 10.0);
    r.psd_pass = psd_pass;
    rows.push_back(r);
  }
  ChannelExtras extra;
  extra.channel = t.name;
  extra.truth_has_gm = !t.gauss_markov.empty();
  extra.truth_has_lines = !t.lines.empty();
  // Gauss–Markov: each truth term takes the unmatched fitted one nearest in ln T_c, within ×3.
  std::vector<bool> gm_used(axis ? axis->gauss_markov.size() : 0, false);
  for (const GaussMarkovSpec& g : t.gauss_markov) {
    std::optional<std::size_t> best;
    double best_distance = std::log(3.0);
    for (std::size_t j = 0; j < gm_used.size(); ++j) {
      const double distance = std::abs(std::log(axis->gauss_markov[j].value.tau_c_s / g.tau_c_s));
      if (!gm_used[j] && distance <= best_distance) {
        best = j;
        best_distance = distance;
      }
    }
    ScoreRow sigma, tau;
    sigma.channel = tau.channel = t.name;
    sigma.term = Coefficient::gm_sigma;
    tau.term = Coefficient::gm_tau_c;
    sigma.truth = sigma.truth_as_recorded = g.sigma;
    tau.truth = tau.truth_as_recorded = g.tau_c_s;
    sigma.frequency_hz = tau.frequency_hz = g.tau_c_s;
    sigma.psd_pass = tau.psd_pass = psd_pass;
    if (best) {
      gm_used[*best] = true;
      const models::GaussMarkovEstimate& e = axis->gauss_markov[*best];
      sigma.identified = tau.identified = true;
      sigma.has_interval = tau.has_interval = true;
      sigma.estimate = e.value.sigma;
      sigma.ci_low = e.sigma_ci_low;
      sigma.ci_high = e.sigma_ci_high;
      tau.estimate = e.value.tau_c_s;
      tau.ci_low = e.tau_c_ci_low_s;
      tau.ci_high = e.tau_c_ci_high_s;
      sigma.covered = sigma.ci_low <= g.sigma && g.sigma <= sigma.ci_high;
      tau.covered = tau.ci_low <= g.tau_c_s && g.tau_c_s <= tau.ci_high;
    } else if (const std::optional<double> bound =
                   axis ? gauss_markov_bound_at(*axis, g.tau_c_s) : std::nullopt) {
      // Not identified: model.yaml's upper-bound curve excludes the GMs above it. The truth
      // is covered when it lies below the curve — one joint statement on (σ, T_c), scored on
      // both rows (its T_c projection is every T_c), as a power-law term not identified is
      // covered by [0, its upper bound].
      sigma.has_interval = tau.has_interval = true;
      sigma.ci_high = *bound;
      tau.ci_high = std::numeric_limits<double>::infinity();
      sigma.covered = tau.covered = g.sigma <= *bound;
    }
    rows.push_back(sigma);
    rows.push_back(tau);
  }
  extra.false_gm = static_cast<int>(std::count(gm_used.begin(), gm_used.end(), false));
  // Lines: match by frequency within max(2 %, 2/T); the amplitude interval is model.yaml's
  // amplitude_ci_low/high (a file without them reads as an empty interval at the amplitude).
  std::vector<bool> line_used(axis ? axis->sinusoids.size() : 0, false);
  for (const TruthLine& l : t.lines) {
    std::optional<std::size_t> best;
    double best_distance = std::max(0.02 * l.frequency_hz, 2.0 / length);
    for (std::size_t j = 0; j < line_used.size(); ++j) {
      const double distance = std::abs(axis->sinusoids[j].value.frequency_hz - l.frequency_hz);
      if (!line_used[j] && distance <= best_distance) {
        best = j;
        best_distance = distance;
      }
    }
    ScoreRow r;
    r.channel = t.name;
    r.term = Coefficient::sinusoid_amplitude;
    r.truth = r.truth_as_recorded = l.amplitude;
    r.frequency_hz = l.frequency_hz;
    r.line_snr = l.snr;
    r.psd_pass = psd_pass;
    if (best) {
      line_used[*best] = true;
      const models::SinusoidEstimate& e = axis->sinusoids[*best];
      r.identified = true;
      r.estimate = std::abs(e.value.amplitude);
      r.ci_low = e.amplitude_ci_low;
      r.ci_high = e.amplitude_ci_high;
      r.has_interval = r.ci_high > r.ci_low;
      r.covered = r.has_interval && r.ci_low <= l.amplitude && l.amplitude <= r.ci_high;
    }
    rows.push_back(r);
  }
  extra.false_lines = static_cast<int>(std::count(line_used.begin(), line_used.end(), false));
  extras.push_back(extra);
}

/// Case-insensitive patterns naming each phenomenon in a finding (docs/validation.md).
const std::array<std::regex, kPhenomena.size()>& finding_patterns() {
  static const auto flags = std::regex::icase | std::regex::ECMAScript;
  static const std::array<std::regex, kPhenomena.size()> patterns = {
      std::regex(R"(warm-?\s?up|thermal transient|start-up transient|--trim-start)", flags),
      std::regex(R"(outlier|spike)", flags),
      std::regex(R"(low-?pass|roll-?off|filter corner|bandwidth)", flags),
      std::regex(R"(decimat|without averaging)", flags),
      // Quantized stamps named as such (a plain "time-stamp jitter" line does not count).
      std::regex(R"((stamp|time).{0,40}quantiz|quantiz.{0,40}(stamp|time)|mean interval)", flags),
      // The rate LSB, not that of an extra column ("temperature: output quantized, LSB …").
      std::regex(R"(^(?!temperature:).*(\blsb\b|output quantiz))", flags),
      std::regex(R"(spectral line|\blines? (at|found)|sinusoid)", flags),
      std::regex(R"(temperature(?!: output quantized))", flags)};
  return patterns;
}

std::string percent(double fraction) {
  if (!std::isfinite(fraction)) return "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * fraction);
  return buf;
}

/// "k/n = p % ± se" with the binomial standard error.
std::string rate_text(int k, int n) {
  if (n == 0) return "—";
  const double p = static_cast<double>(k) / n;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%d/%d = %.1f %% ± %.1f", k, n, 100.0 * p,
                100.0 * std::sqrt(p * (1.0 - p) / n));
  return buf;
}

std::string number(double v, const char* format = "%.3g") {
  if (!std::isfinite(v)) return "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + "\"";
}

std::string g17(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

/// Classes in the order they first appear.
std::vector<std::string> classes_of(const std::vector<RecordingResult>& results) {
  std::vector<std::string> out;
  for (const RecordingResult& r : results) {
    if (std::find(out.begin(), out.end(), r.class_name) == out.end()) out.push_back(r.class_name);
  }
  return out;
}

struct Tally {
  int truth_rows = 0, with_interval = 0, covered = 0, identified = 0;
  std::vector<double> errors, readoff_errors;
};

Tally tally(const std::vector<RecordingResult>& results, Coefficient c, const std::string& cls) {
  Tally t;
  for (const RecordingResult& r : results) {
    if (!cls.empty() && r.class_name != cls) continue;
    for (const ScoreRow& row : r.rows) {
      if (row.term != c || row.truth <= 0.0) continue;
      ++t.truth_rows;
      t.with_interval += row.has_interval;
      t.covered += row.covered;
      t.identified += row.identified;
      if (row.identified) t.errors.push_back(std::abs(row.estimate / row.truth - 1.0));
      if (row.readoff > 0.0) t.readoff_errors.push_back(std::abs(row.readoff / row.truth - 1.0));
    }
  }
  return t;
}

struct Count {
  int k = 0, n = 0;
  double rate() const {
    return n ? static_cast<double>(k) / n : std::numeric_limits<double>::quiet_NaN();
  }
};

/// Channel-terms the truth lacks (power-law terms, "any GM", "any line") reported identified.
Count false_terms(const std::vector<RecordingResult>& results) {
  Count c;
  for (const RecordingResult& r : results) {
    for (const ScoreRow& row : r.rows) {
      if (row.truth > 0.0 || row.term > Coefficient::ramp) continue;
      ++c.n;
      c.k += row.identified;
    }
    for (const ChannelExtras& e : r.extras) {
      if (!e.truth_has_gm) {
        ++c.n;
        c.k += e.false_gm > 0;
      }
      if (!e.truth_has_lines) {
        ++c.n;
        c.k += e.false_lines > 0;
      }
    }
  }
  return c;
}

Count k_identification(const std::vector<RecordingResult>& results) {
  Count c;
  for (const RecordingResult& r : results) {
    for (const ScoreRow& row : r.rows) {
      if (row.term == Coefficient::random_walk && row.truth > 0.0 && row.k_share_t10 >= 0.6) {
        ++c.n;
        c.k += row.identified;
      }
    }
  }
  return c;
}

Count psd_passes(const std::vector<RecordingResult>& results) {
  Count c;
  for (const RecordingResult& r : results) {
    std::set<std::string> seen;
    for (const ScoreRow& row : r.rows) {
      if (!row.psd_pass || !seen.insert(row.channel).second) continue;
      ++c.n;
      c.k += *row.psd_pass;
    }
  }
  return c;
}

}  // namespace

const char* coefficient_label(Coefficient c) {
  static const char* labels[] = {"Q", "N", "B", "K", "R", "GM σ", "GM T_c", "sine A"};
  return labels[static_cast<int>(c)];
}

const char* coefficient_key(Coefficient c) {
  static const char* keys[] = {
      "quantization", "white_noise", "bias_instability", "random_walk",
      "ramp",         "gm_sigma",    "gm_tau_c",         "sinusoid_amplitude"};
  return keys[static_cast<int>(c)];
}

std::vector<ScoreRow> score_model(const BatteryCase& c, const models::NoiseModel& model,
                                  std::vector<ChannelExtras>& extras) {
  std::vector<ScoreRow> rows;
  for (const ChannelTruth& t : c.truth) score_channel(c, t, model.find_axis(t.name), rows, extras);
  return rows;
}

std::vector<ScoreRow> score_failure(const BatteryCase& c, std::vector<ChannelExtras>& extras) {
  std::vector<ScoreRow> rows;
  for (const ChannelTruth& t : c.truth) score_channel(c, t, nullptr, rows, extras);
  return rows;
}

std::array<bool, kPhenomena.size()> findings_present(const models::NoiseModel& model) {
  std::vector<std::string> texts = model.data_quality;
  for (const models::AxisModel& a : model.axes) {
    texts.push_back(a.fit_note);
    texts.push_back(a.psd_check_note);
  }
  std::array<bool, kPhenomena.size()> found{};
  for (std::size_t p = 0; p < kPhenomena.size(); ++p) {
    for (const std::string& s : texts)
      found[p] = found[p] || std::regex_search(s, finding_patterns()[p]);
  }
  return found;
}

std::string rows_csv(const std::vector<RecordingResult>& results) {
  std::ostringstream out;
  out << "class,grade,seed,rate_hz,duration_s,channel,term,truth,truth_as_recorded,estimate,"
         "ci_low,ci_high,has_interval,identified,covered,rel_error,readoff_ieee952,"
         "readoff_rel_error,truth_f_hz_or_tau_c_s,line_snr,k_share_t10,psd_pass,analyze_s\n";
  for (const RecordingResult& r : results) {
    for (const ScoreRow& row : r.rows) {
      const bool rel = row.truth > 0.0 && row.identified;
      out << r.class_name << ',' << r.grade << ',' << r.seed << ',' << g17(r.rate_hz) << ','
          << g17(r.duration_s) << ',' << row.channel << ',' << coefficient_key(row.term) << ','
          << g17(row.truth) << ',' << g17(row.truth_as_recorded) << ',' << g17(row.estimate) << ','
          << (row.has_interval ? g17(row.ci_low) : "") << ','
          << (row.has_interval ? g17(row.ci_high) : "") << ',' << row.has_interval << ','
          << row.identified << ',' << row.covered << ','
          << (rel ? g17(row.estimate / row.truth - 1.0) : "") << ',' << g17(row.readoff) << ','
          << (row.truth > 0.0 && row.readoff > 0.0 ? g17(row.readoff / row.truth - 1.0) : "") << ','
          << g17(row.frequency_hz) << ',' << g17(row.line_snr) << ',' << g17(row.k_share_t10) << ','
          << (row.psd_pass ? (*row.psd_pass ? "1" : "0") : "") << ',' << g17(r.analyze_s) << '\n';
    }
  }
  return out.str();
}

std::string recordings_csv(const std::vector<RecordingResult>& results) {
  std::ostringstream out;
  out << "class,grade,seed,rate_hz,duration_s,generate_s,write_s,analyze_s,exit_code";
  for (Phenomenon p : kPhenomena) out << ",finding_" << phenomenon_name(p);
  out << ",phenomena,findings\n";
  for (const RecordingResult& r : results) {
    out << r.class_name << ',' << r.grade << ',' << r.seed << ',' << g17(r.rate_hz) << ','
        << g17(r.duration_s) << ',' << g17(r.generate_s) << ',' << g17(r.write_s) << ','
        << g17(r.analyze_s) << ',' << r.exit_code;
    for (bool f : r.findings) out << ',' << f;
    std::string phen, lines;
    for (Phenomenon p : r.phenomena)
      phen += std::string(phen.empty() ? "" : " ") + phenomenon_name(p);
    for (const std::string& l : r.finding_lines) lines += (lines.empty() ? "" : " | ") + l;
    out << ',' << csv_field(phen) << ',' << csv_field(lines) << '\n';
  }
  return out.str();
}

std::string summary_markdown(const std::vector<RecordingResult>& results,
                             const std::string& title) {
  std::ostringstream md;
  const std::vector<std::string> classes = classes_of(results);
  int failures = 0;
  for (const RecordingResult& r : results) failures += r.exit_code != 0;
  md << "## " << title << "\n\n"
     << results.size() << " recordings, " << classes.size() << " classes, " << failures
     << " failed analyses.\n\n";

  md << "### Coverage of the 95 % intervals, identification and error (all classes)\n\n"
     << "| coefficient | truth rows | with interval | covered ± SE | identified | median "
        "\\|rel. error\\| (identified) | IEEE-952 read-off median \\|rel. error\\| (found) |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (Coefficient c : kCoefficients) {
    const Tally t = tally(results, c, "");
    if (t.truth_rows == 0) continue;
    md << "| " << coefficient_label(c) << " | " << t.truth_rows << " | " << t.with_interval << " | "
       << rate_text(t.covered, t.truth_rows) << " | " << rate_text(t.identified, t.truth_rows)
       << " | " << percent(median(t.errors)) << " (" << t.errors.size() << ") | "
       << (t.readoff_errors.empty() ? std::string("—")
                                    : percent(median(t.readoff_errors)) + " (" +
                                          std::to_string(t.readoff_errors.size()) + ")")
       << " |\n";
  }

  md << "\n### Coverage per class (covered/truth rows)\n\n| class |";
  for (Coefficient c : kCoefficients) md << ' ' << coefficient_label(c) << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < kCoefficients.size(); ++i) md << "---|";
  md << '\n';
  for (const std::string& cls : classes) {
    md << "| " << cls << " |";
    for (Coefficient c : kCoefficients) {
      const Tally t = tally(results, c, cls);
      md << ' '
         << (t.truth_rows ? std::to_string(t.covered) + "/" + std::to_string(t.truth_rows) : "—")
         << " |";
    }
    md << '\n';
  }

  md << "\n### Median |relative error| per class where identified (IEEE-952 read-off in "
        "brackets)\n\n| class | N | B | K |\n|---|---|---|---|\n";
  for (const std::string& cls : classes) {
    md << "| " << cls << " |";
    for (Coefficient c :
         {Coefficient::white_noise, Coefficient::bias_instability, Coefficient::random_walk}) {
      const Tally t = tally(results, c, cls);
      md << ' '
         << (t.truth_rows
                 ? percent(median(t.errors)) + " [" + percent(median(t.readoff_errors)) + "]"
                 : std::string("—"))
         << " |";
    }
    md << '\n';
  }

  // False terms: a channel-term the truth lacks, reported as identified.
  md << "\n### Terms the truth lacks, reported as identified (per channel-term)\n\n"
     << "| term | opportunities | false | rate ± SE |\n|---|---|---|---|\n";
  int all_opportunities = 0, all_false = 0;
  std::map<std::string, std::pair<int, int>> per_class;  // class → (false, opportunities)
  for (Coefficient c : kPowerLawCoefficients) {
    int opportunities = 0, false_terms = 0;
    for (const RecordingResult& r : results) {
      for (const ScoreRow& row : r.rows) {
        if (row.term != c || row.truth > 0.0) continue;
        ++opportunities;
        false_terms += row.identified;
        per_class[r.class_name].first += row.identified;
        ++per_class[r.class_name].second;
      }
    }
    all_opportunities += opportunities;
    all_false += false_terms;
    md << "| " << coefficient_label(c) << " | " << opportunities << " | " << false_terms << " | "
       << rate_text(false_terms, opportunities) << " |\n";
  }
  for (bool gm : {true, false}) {
    int opportunities = 0, false_terms = 0, extra = 0;
    for (const RecordingResult& r : results) {
      for (const ChannelExtras& e : r.extras) {
        const bool truth_has = gm ? e.truth_has_gm : e.truth_has_lines;
        const int spurious = gm ? e.false_gm : e.false_lines;
        if (truth_has) {
          extra += spurious;
          continue;
        }
        ++opportunities;
        false_terms += spurious > 0;
        per_class[r.class_name].first += spurious > 0;
        ++per_class[r.class_name].second;
      }
    }
    all_opportunities += opportunities;
    all_false += false_terms;
    md << "| " << (gm ? "GM (any)" : "line (any)") << " | " << opportunities << " | " << false_terms
       << " | " << rate_text(false_terms, opportunities) << " |\n";
    md << "| " << (gm ? "GM beyond the truth's" : "lines beyond the truth's")
       << " (channels that have them) | — | " << extra << " | — |\n";
  }
  md << "| **all** | " << all_opportunities << " | " << all_false << " | "
     << rate_text(all_false, all_opportunities) << " |\n\nPer class: ";
  for (const std::string& cls : classes) {
    md << cls << " " << per_class[cls].first << "/" << per_class[cls].second << "; ";
  }
  md << "\n";

  md << "\n### K identified where K carries ≥ 60 % of the AVAR at T/10\n\n"
     << "| class | channels | K identified ± SE |\n|---|---|---|\n";
  int k_all = 0, k_found = 0;
  for (const std::string& cls : classes) {
    int n = 0, found = 0;
    for (const RecordingResult& r : results) {
      if (r.class_name != cls) continue;
      for (const ScoreRow& row : r.rows) {
        if (row.term == Coefficient::random_walk && row.truth > 0.0 && row.k_share_t10 >= 0.6) {
          ++n;
          found += row.identified;
        }
      }
    }
    k_all += n;
    k_found += found;
    if (n) md << "| " << cls << " | " << n << " | " << rate_text(found, n) << " |\n";
  }
  md << "| **all** | " << k_all << " | " << rate_text(k_found, k_all) << " |\n";

  md << "\n### Lines (truth lines found, by SNR in a T/16 bin; false lines per channel)\n\n"
     << "| SNR | lines | found ± SE | median \\|A error\\| (found) |\n|---|---|---|---|\n";
  std::map<double, std::pair<int, int>> by_snr;
  std::map<double, std::vector<double>> snr_errors;
  int channels = 0, false_lines = 0;
  for (const RecordingResult& r : results) {
    for (const ScoreRow& row : r.rows) {
      if (row.term != Coefficient::sinusoid_amplitude) continue;
      ++by_snr[row.line_snr].second;
      by_snr[row.line_snr].first += row.identified;
      if (row.identified)
        snr_errors[row.line_snr].push_back(std::abs(row.estimate / row.truth - 1));
    }
    for (const ChannelExtras& e : r.extras) {
      ++channels;
      false_lines += e.false_lines;
    }
  }
  for (const auto& [snr, counts] : by_snr) {
    md << "| " << number(snr) << " | " << counts.second << " | "
       << rate_text(counts.first, counts.second) << " | " << percent(median(snr_errors[snr]))
       << " |\n";
  }
  md << "\nFalse lines: " << false_lines << " in " << channels << " channels ("
     << number(channels ? 10.0 * false_lines / channels : 0.0) << " per 10 channels).\n";

  md << "\n### PSD cross-check passed (channels with a verdict)\n\n| class | passed ± SE "
        "|\n|---|---|\n";
  int psd_all = 0, psd_pass = 0;
  for (const std::string& cls : classes) {
    int n = 0, pass = 0;
    for (const RecordingResult& r : results) {
      if (r.class_name != cls) continue;
      std::set<std::string> seen;
      for (const ScoreRow& row : r.rows) {
        if (!row.psd_pass || !seen.insert(row.channel).second) continue;
        ++n;
        pass += *row.psd_pass;
      }
    }
    psd_all += n;
    psd_pass += pass;
    md << "| " << cls << " | " << rate_text(pass, n) << " |\n";
  }
  md << "| **all** | " << rate_text(psd_pass, psd_all) << " |\n";

  md << "\n### Data-quality findings per phenomenon (recordings with the finding / recordings; "
        "**bold**: the class has the phenomenon)\n\n| class |";
  for (Phenomenon p : kPhenomena) md << ' ' << phenomenon_name(p) << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < kPhenomena.size(); ++i) md << "---|";
  md << '\n';
  for (const std::string& cls : classes) {
    md << "| " << cls << " |";
    for (std::size_t p = 0; p < kPhenomena.size(); ++p) {
      int n = 0, found = 0;
      bool has = false;
      for (const RecordingResult& r : results) {
        if (r.class_name != cls) continue;
        ++n;
        found += r.findings[p];
        has = has ||
              std::find(r.phenomena.begin(), r.phenomena.end(), kPhenomena[p]) != r.phenomena.end();
      }
      const std::string cell = std::to_string(found) + "/" + std::to_string(n);
      md << ' ' << (has ? "**" + cell + "**" : cell) << " |";
    }
    md << '\n';
  }

  md << "\n### Wall time\n\n| class | recordings | rate [Hz] | length [h] | generate [s] | write "
        "[s] | analyze [s] (mean) | analyze [s] (max) |\n|---|---|---|---|---|---|---|---|\n";
  double total_analyze = 0.0, total_generate = 0.0;
  for (const std::string& cls : classes) {
    int n = 0;
    double gen = 0.0, wr = 0.0, an = 0.0, an_max = 0.0, rate = 0.0, length = 0.0;
    for (const RecordingResult& r : results) {
      if (r.class_name != cls) continue;
      ++n;
      gen += r.generate_s;
      wr += r.write_s;
      an += r.analyze_s;
      an_max = std::max(an_max, r.analyze_s);
      rate = r.rate_hz;
      length = r.duration_s / 3600.0;
    }
    total_analyze += an;
    total_generate += gen + wr;
    md << "| " << cls << " | " << n << " | " << number(rate, "%.4g") << " | "
       << number(length, "%.3g") << " | " << number(gen / n, "%.2f") << " | "
       << number(wr / n, "%.2f") << " | " << number(an / n, "%.2f") << " | "
       << number(an_max, "%.2f") << " |\n";
  }
  md << "\nTotal: analyze " << number(total_analyze, "%.0f") << " s, generate + write "
     << number(total_generate, "%.0f") << " s.\n";
  bool all_met = false;
  md << "\n### Acceptance (issue 20 targets this battery measures)\n\n"
     << acceptance_markdown(results, all_met);
  return md.str();
}

}  // namespace imunoise::battery

namespace imunoise::battery {

std::string acceptance_markdown(const std::vector<RecordingResult>& results, bool& all_met) {
  std::ostringstream md;
  all_met = true;
  // MET empty: nothing in RESULTS measures the target.
  const auto row = [&](const std::string& target, const std::string& measured,
                       std::optional<bool> met) {
    md << "| " << target << " | " << measured << " | "
       << (!met   ? "not measured"
           : *met ? "met"
                  : "**not met**")
       << " |\n";
    all_met = all_met && met.value_or(true);
  };
  const auto when = [](bool measured, bool met) {
    return measured ? std::optional<bool>(met) : std::nullopt;
  };
  md << "| target (issue 20) | measured | |\n|---|---|---|\n";
  for (Coefficient c : kCoefficients) {
    const Tally t = tally(results, c, "");
    if (t.truth_rows == 0) continue;
    const double p = static_cast<double>(t.covered) / t.truth_rows;
    row(std::string(coefficient_label(c)) + " covered 95 ± 5 %", rate_text(t.covered, t.truth_rows),
        p >= 0.90 && p <= 1.0);
  }
  const Count f = false_terms(results);
  row("terms the truth lacks identified ≤ 2 % of channel-terms", rate_text(f.k, f.n),
      when(f.n > 0, f.rate() <= 0.02));
  const Count k = k_identification(results);
  row("K identified ≥ 80 % where it carries ≥ 60 % of the AVAR at T/10", rate_text(k.k, k.n),
      when(k.n > 0, k.rate() >= 0.80));
  const Count psd = psd_passes(results);
  row("PSD cross-check passed ≥ 95 % of channels", rate_text(psd.k, psd.n),
      when(psd.n > 0, psd.rate() >= 0.95));
  Count lines;
  int channels = 0, false_lines = 0;
  for (const RecordingResult& r : results) {
    for (const ScoreRow& rw : r.rows) {
      if (rw.term != Coefficient::sinusoid_amplitude || rw.line_snr < 10.0) continue;
      ++lines.n;
      lines.k += rw.identified;
    }
    for (const ChannelExtras& e : r.extras) {
      ++channels;
      false_lines += e.false_lines;
    }
  }
  if (lines.n)
    row("lines with SNR ≥ 10 (T/16 bin) found ≥ 90 %", rate_text(lines.k, lines.n),
        lines.rate() >= 0.90);
  row("≤ 1 false line per 10 channels",
      std::to_string(false_lines) + " in " + std::to_string(channels) + " channels",
      10 * false_lines <= channels);
  for (Phenomenon p : {Phenomenon::warmup, Phenomenon::outliers, Phenomenon::low_pass,
                       Phenomenon::decimation, Phenomenon::stamps}) {
    const std::size_t i = static_cast<std::size_t>(p);
    Count with, without;
    for (const RecordingResult& r : results) {
      const bool has = std::find(r.phenomena.begin(), r.phenomena.end(), p) != r.phenomena.end();
      Count& c = has ? with : without;
      ++c.n;
      c.k += r.findings[i];
    }
    row(std::string(phenomenon_name(p)) + " finding on every case with it, none without",
        std::to_string(with.k) + "/" + std::to_string(with.n) + " with, " +
            std::to_string(without.k) + "/" + std::to_string(without.n) + " without",
        when(with.n > 0, with.k == with.n && without.k == 0));
  }
  const std::array<std::pair<Coefficient, double>, 3> error_targets = {
      {{Coefficient::white_noise, 0.005},
       {Coefficient::bias_instability, 0.05},
       {Coefficient::random_walk, 0.15}}};
  for (const auto& [c, limit] : error_targets) {
    const Tally t = tally(results, c, "");
    const double e = median(t.errors), r = median(t.readoff_errors);
    row(std::string("median \\|error\\| of ") + coefficient_label(c) + " ≤ " + percent(limit) +
            " and below the IEEE-952 read-off's",
        percent(e) + " vs read-off " + percent(r),
        when(t.errors.size() > 0, e <= limit && (!(r >= 0.0) || e < r)));
  }
  return md.str();
}

}  // namespace imunoise::battery
