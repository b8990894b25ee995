#include "pipeline/low_pass_corner.h"

#include <cmath>
#include <vector>

#include "analysis/psd_model.h"

namespace imunoise::pipeline {

LowPassCorner find_low_pass_corner(const analysis::Spectrum& psd, const NoiseCoefficients& model,
                                   double tau0_s) {
  LowPassCorner out;
  const double nyquist = 0.5 / tau0_s;
  std::vector<double> f, ratio;
  for (std::size_t i = 0; i < psd.frequency_hz.size(); ++i) {
    const double fi = psd.frequency_hz[i];
    if (!(fi >= 0.05 * nyquist && fi <= nyquist)) continue;
    const double m = analysis::model_psd_one_sided(model, fi, tau0_s);
    if (!(m > 0.0) || !std::isfinite(m) || !std::isfinite(psd.density[i])) continue;
    f.push_back(fi);
    ratio.push_back(psd.density[i] / m);
  }
  if (f.size() < static_cast<std::size_t>(kLowPassTopBins) + 1) return out;
  out.ratio_at_top = ratio.back();
  // Walk down from the top while the bins stay below half the model.
  std::size_t first_below = f.size();
  while (first_below > 0 && ratio[first_below - 1] < 0.5) --first_below;
  if (f.size() - first_below < static_cast<std::size_t>(kLowPassTopBins) || first_below == 0) {
    return out;
  }
  out.found = true;
  // −3 dB between bin first_below − 1 (≥ 1/2) and first_below (< 1/2), linear in log f and
  // log ratio.
  const double r0 = std::log(ratio[first_below - 1]), r1 = std::log(ratio[first_below]);
  const double l0 = std::log(f[first_below - 1]), l1 = std::log(f[first_below]);
  const double t = r0 > r1 ? (r0 - std::log(0.5)) / (r0 - r1) : 0.5;
  out.corner_hz = std::exp(l0 + t * (l1 - l0));
  return out;
}

}  // namespace imunoise::pipeline
