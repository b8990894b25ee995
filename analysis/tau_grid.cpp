#include "analysis/tau_grid.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "analysis/total_family.h"
#include "common/errors.h"

namespace imunoise::analysis {

namespace {

std::int64_t parse_positive_integer(std::string_view token, std::string_view whole) {
  std::int64_t value = 0;
  const auto* first = token.data();
  const auto* last = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last || value < 1) {
    throw InputError("invalid tau grid '" + std::string(whole) + "': '" + std::string(token) +
                     "' is not a positive integer averaging factor (expected octave, decade, "
                     "all, log:N or a list like 1,2,10)");
  }
  return value;
}

// Cost guard for the O(M) per τ kernels: 'all' on a long record would run for hours.
constexpr double kMaxAllGridWork = 2e10;
// Cost guard for the O(M·m) estimators (total family, Thêo1): ~1 ns per inner operation,
// so 3e10 operations is about half a minute.
constexpr double kMaxQuadraticWork = 3e10;

/// Inner operations of one τ of an O(M·m) estimator: windows × work per window (the total
/// family detrends and reflects 9m points per window; Thêo1 sums m/2 lags per term).
double quadratic_work(DeviationType type, std::int64_t n_phase, std::int64_t m) {
  const double n = static_cast<double>(estimator_term_count(type, n_phase, m));
  return type == DeviationType::theo1 ? n : 9.0 * n * static_cast<double>(m);
}

}  // namespace

TauGridSpec parse_tau_grid(std::string_view text) {
  TauGridSpec spec;
  if (text == "octave") {
    spec.kind = TauGridSpec::Kind::octave;
  } else if (text == "decade") {
    spec.kind = TauGridSpec::Kind::decade;
  } else if (text == "all") {
    spec.kind = TauGridSpec::Kind::all;
  } else if (text.rfind("log:", 0) == 0) {
    spec.kind = TauGridSpec::Kind::log;
    const std::int64_t n = parse_positive_integer(text.substr(4), text);
    if (n > 1000) {
      throw InputError("invalid tau grid '" + std::string(text) +
                       "': at most 1000 points per decade");
    }
    spec.per_decade = static_cast<int>(n);
  } else {
    spec.kind = TauGridSpec::Kind::explicit_list;
    if (text.empty()) throw InputError("empty tau grid");
    std::size_t start = 0;
    while (start <= text.size()) {
      const std::size_t comma = text.find(',', start);
      const std::size_t end = comma == std::string_view::npos ? text.size() : comma;
      spec.factors.push_back(parse_positive_integer(text.substr(start, end - start), text));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    std::sort(spec.factors.begin(), spec.factors.end());
    spec.factors.erase(std::unique(spec.factors.begin(), spec.factors.end()), spec.factors.end());
  }
  return spec;
}

std::int64_t estimator_term_count(DeviationType type, std::int64_t n_phase, std::int64_t m) {
  const std::int64_t M = n_phase;
  if (m < 1 || M < 2) return 0;
  std::int64_t n = 0;
  switch (type) {
    case DeviationType::adev:
      n = (M - 1) / m - 1;  // ⌊(M−1)/m⌋ clusters, one fewer first differences
      break;
    case DeviationType::oadev:
      n = M - 2 * m;
      break;
    case DeviationType::mdev:
    case DeviationType::tdev:
      n = M - 3 * m + 1;
      break;
    case DeviationType::hdev:
      n = (M - 1) / m - 2;
      break;
    case DeviationType::ohdev:
      n = M - 3 * m;
      break;
    case DeviationType::mtotdev:
    case DeviationType::ttotdev:
    case DeviationType::htotdev:
      n = m <= total_family_max_m(*total_family_type(type), M)
              ? total_family_term_count(*total_family_type(type), M, m)
              : 0;
      break;
    case DeviationType::theo1:
      // SP 1065 eq. 30: (M − m) positions × m/2 lags; m even, m ≤ M − 1.
      // The product reaches 2^63 near M ≈ 10^10 at the largest m: saturate instead of wrapping.
      if (m % 2 == 0 && m <= M - 1) {
        const std::int64_t half = m / 2;
        n = M - m > std::numeric_limits<std::int64_t>::max() / half
                ? std::numeric_limits<std::int64_t>::max()
                : (M - m) * half;
      }
      break;
    case DeviationType::totdev:
      // The reflected extension provides neighbours for every interior point, but it is only
      // defined for m ≤ M − 2 (theory.md §2, reflection j = 1..M−2).
      n = (M >= 3 && m <= M - 2) ? M - 2 : 0;
      break;
  }
  return std::max<std::int64_t>(n, 0);
}

std::int64_t max_averaging_factor(DeviationType type, std::int64_t n_phase) {
  std::int64_t m = n_phase / stop_ratio(type);
  if (type == DeviationType::theo1) m -= m % 2;  // Thêo1 needs even m
  while (m >= 1 && estimator_term_count(type, n_phase, m) < 1)
    m -= type == DeviationType::theo1 ? 2 : 1;
  return std::max<std::int64_t>(m, 0);
}

std::vector<std::int64_t> averaging_factors(const TauGridSpec& spec, DeviationType type,
                                            std::int64_t n_phase) {
  const std::int64_t max_m = max_averaging_factor(type, n_phase);
  if (max_m < 1) {
    throw AnalysisError("too few samples for " + std::string(to_string(type)) + ": " +
                        std::to_string(n_phase) + " phase samples (" +
                        std::to_string(std::max<std::int64_t>(n_phase - 1, 0)) +
                        " rate samples) do not give a single estimate even at tau = tau0 (at "
                        "least " +
                        std::to_string(stop_ratio(type)) + " phase samples are needed)");
  }
  std::vector<std::int64_t> out;
  switch (spec.kind) {
    case TauGridSpec::Kind::octave:
      for (std::int64_t m = 1; m <= max_m; m *= 2) out.push_back(m);
      break;
    case TauGridSpec::Kind::decade:
      for (std::int64_t decade = 1; decade <= max_m; decade *= 10) {
        for (std::int64_t k : {1, 2, 4}) {
          if (k * decade <= max_m) out.push_back(k * decade);
        }
      }
      break;
    case TauGridSpec::Kind::all: {
      const double work = static_cast<double>(max_m) * static_cast<double>(n_phase);
      if (work > kMaxAllGridWork) {
        throw AnalysisError("the 'all' tau grid on " + std::to_string(n_phase) + " samples needs " +
                            std::to_string(max_m) +
                            " passes over the data; use log:N (e.g. log:100) instead");
      }
      for (std::int64_t m = 1; m <= max_m; ++m) out.push_back(m);
      break;
    }
    case TauGridSpec::Kind::log: {
      const double step = 1.0 / spec.per_decade;
      for (int i = 0;; ++i) {
        const double mf = std::round(std::pow(10.0, i * step));
        if (mf > static_cast<double>(max_m)) break;
        const auto m = static_cast<std::int64_t>(mf);
        if (out.empty() || out.back() != m) out.push_back(m);
      }
      break;
    }
    case TauGridSpec::Kind::explicit_list:
      for (std::int64_t m : spec.factors) {
        if (type == DeviationType::theo1 && m % 2 != 0) {
          throw AnalysisError("theo1 needs even averaging factors (tau = 0.75·m·tau0); got m = " +
                              std::to_string(m));
        }
        if (m > max_m) {
          // m comes from the command line: m·r may not fit in 64 bits.
          const std::int64_t ratio = stop_ratio(type);
          const std::string needed = m <= std::numeric_limits<std::int64_t>::max() / ratio
                                         ? std::to_string(m * ratio)
                                         : std::string("more than 2^63");
          throw AnalysisError(
              "too few samples for the requested tau: m = " + std::to_string(m) +
              " needs at least " + needed + " phase samples for " + std::string(to_string(type)) +
              " (stop ratio " + std::to_string(stop_ratio(type)) + "), the data has " +
              std::to_string(n_phase) + "; the largest usable m is " + std::to_string(max_m));
        }
        out.push_back(m);
      }
      break;
  }
  if (type == DeviationType::theo1) {
    // Thêo1 is defined for even m only: move odd grid points up to the next even factor.
    std::vector<std::int64_t> even;
    for (std::int64_t m : out) {
      const std::int64_t e = m + (m % 2);
      if (e <= max_m && (even.empty() || even.back() != e)) even.push_back(e);
    }
    out = std::move(even);
  }
  if (cost_grows_with_m(type)) {
    double work = 0.0;
    for (std::int64_t m : out) work += quadratic_work(type, n_phase, m);
    if (work > kMaxQuadraticWork) {
      throw AnalysisError(std::string(to_string(type)) + " costs O(M·m) per tau: this grid on " +
                          std::to_string(n_phase) + " samples needs about " +
                          std::to_string(static_cast<long long>(work / 1e9)) +
                          "e9 operations (limit 30e9); use fewer or smaller averaging factors "
                          "(an explicit list) or a shorter record");
    }
  }
  return out;
}

std::string to_string(const TauGridSpec& spec) {
  switch (spec.kind) {
    case TauGridSpec::Kind::octave:
      return "octave";
    case TauGridSpec::Kind::decade:
      return "decade";
    case TauGridSpec::Kind::all:
      return "all";
    case TauGridSpec::Kind::log:
      return "log:" + std::to_string(spec.per_decade);
    case TauGridSpec::Kind::explicit_list: {
      std::string s;
      for (std::size_t i = 0; i < spec.factors.size(); ++i) {
        if (i) s += ",";
        s += std::to_string(spec.factors[i]);
      }
      return s;
    }
  }
  return "";
}

}  // namespace imunoise::analysis
