/// @file
/// @brief The corner of a sensor's low-pass filter (a MEMS digital low-pass, an anti-alias
/// filter) from the measured PSD against the fitted model's: the roll-off below the white floor
/// near Nyquist. Pure computation on a spectrum and a model.
#pragma once

#include "analysis/psd.h"
#include "common/noise_coefficients.h"

namespace imunoise::pipeline {

/// A roll-off of the measured PSD below the model near Nyquist.
struct LowPassCorner {
  bool found = false;
  /// The −3 dB point: the lowest frequency above which every compared bin's measured/model
  /// ratio is below 1/2 (log-interpolated between the bins around it) [Hz].
  double corner_hz = 0.0;
  double ratio_at_top = 1.0;  ///< measured/model of the highest bin
};

/// Bins from 0.05·f_Nyquist to f_Nyquist of PSD (one-sided, binned) against
/// analysis::model_psd_one_sided of MODEL at sample period TAU0_S. Found when the highest
/// kLowPassTopBins bins all lie below half the model: a white floor 3 dB down over a band, far
/// beyond the χ² scatter of a log bin (each holds tens of raw bins or more).
LowPassCorner find_low_pass_corner(const analysis::Spectrum& psd, const NoiseCoefficients& model,
                                   double tau0_s);

/// Consecutive top bins below half the model a corner needs.
inline constexpr int kLowPassTopBins = 3;

}  // namespace imunoise::pipeline
