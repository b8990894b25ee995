"""imunoise for Python: Allan-family deviations with intervals, the PSD, the IMU noise fit,
the simulator, every recording reader and the filter exports of the imunoise C++ core.

numpy arrays go in without a copy (float64, C-contiguous; other arrays are converted once),
the GIL is released while the core computes, and errors are Python exceptions carrying the
messages the CLI prints: ``InputError`` (a ValueError: a value you chose is wrong),
``AnalysisError`` (a RuntimeError: the data cannot answer) and ``InternalError`` (a bug).
SI units throughout: rad/s, m/s^2, seconds, Hz. See docs/python.md.
"""
from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass
from typing import Any, Dict, Optional, Sequence, Union

import numpy as np

from . import _core
from ._core import AnalysisError, InputError, InternalError, Recording

__all__ = [
    "AnalysisError", "Deviation", "Estimate", "FitResult", "InputError", "InternalError",
    "Model", "Recording", "Spectrum", "deviation", "export", "fit", "psd", "read_recording",
    "recording_from_arrays", "simulate",
]


@dataclass(frozen=True)
class Deviation:
    """One deviation curve: per averaging factor m, tau [s], the deviation (input unit; TDEV
    and TTOTDEV in phase units), the number of terms of the estimator, the noise exponent alpha
    and EDF behind the interval [ci_low, ci_high] at ``confidence``."""
    kind: str
    confidence: float
    tau0_s: float
    m: np.ndarray
    tau_s: np.ndarray
    value: np.ndarray
    n_terms: np.ndarray
    alpha: np.ndarray
    edf: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray


def deviation(x, kind: str = "oadev", rate: float = 1.0, data: str = "rate",
              taus: Union[str, Sequence[int]] = "octave", confidence: float = 0.683,
              alpha: Optional[int] = None, bias_corrected: bool = False,
              threads: int = 0, tau0_s: Optional[float] = None) -> Deviation:
    """The deviation KIND (adev, oadev, mdev, tdev, hdev, ohdev, totdev, mtotdev, ttotdev,
    htotdev, theo1) of X, rate samples (data='rate') or their integral (data='phase'), sampled
    at RATE [Hz], at the averaging factors of TAUS ('octave', 'decade', 'all', 'log:N' or a
    list of m). Intervals at CONFIDENCE from the EDF of the noise type identified at each tau
    (or ALPHA when given), as `imunoise allan`. TAU0_S, when given, is the sample period
    instead of 1/RATE (e.g. a Recording's sample_period_s, exactly as the CLI takes it)."""
    d = _core.deviation(x, kind, float(rate), data, taus, float(confidence), alpha,
                        bool(bias_corrected), int(threads), tau0_s)
    return Deviation(**d)


@dataclass(frozen=True)
class Spectrum:
    """A one-sided PSD on log-spaced bins: frequency [Hz], density [unit^2/Hz] and the
    equivalent chi-square degrees of freedom of each bin."""
    frequency_hz: np.ndarray
    density: np.ndarray
    dof: np.ndarray
    resolution_hz: float
    segment_length: int
    sample_variance: float
    integrated_power: float


def psd(x, rate: float, bins_per_decade: int = 10, level_segment_length: int = 4096) -> Spectrum:
    """The multi-rate Welch PSD of X sampled at RATE [Hz] (the PSD of `imunoise analyze`)."""
    return Spectrum(**_core.psd(x, float(rate), int(bins_per_decade), int(level_segment_length)))


def read_recording(path: Union[str, os.PathLike], *, topic: Optional[str] = None,
                   instance: Optional[int] = None, time_source: Optional[str] = None,
                   lcm_channel: Optional[str] = None, rate_hz: Optional[float] = None,
                   drop_non_finite: bool = False, threads: int = 0,
                   config: Optional[Union[str, os.PathLike]] = None,
                   time_col: Optional[str] = None, time_unit: Optional[str] = None,
                   gyro_cols: Sequence[str] = (), gyro_unit: Optional[str] = None,
                   accel_cols: Sequence[str] = (), accel_unit: Optional[str] = None) -> Recording:
    """The recording at PATH by the reader its content calls for (CSV/TXT, .imnb, LCM log, ROS 1
    bag, MCAP, rosbag2 .db3, PX4 ULog), as every imunoise command reads it. TOPIC / INSTANCE /
    TIME_SOURCE ('header' or 'log') select in robotics logs, LCM_CHANNEL in LCM logs. For a
    table: RATE_HZ replaces the time column; CONFIG (an input config YAML, as --config) and
    TIME_COL, TIME_UNIT (s, ms, us, ns), GYRO_COLS, GYRO_UNIT (rad/s, deg/s, deg/h, rad, deg),
    ACCEL_COLS, ACCEL_UNIT (m/s^2, g, mg, m/s) map the columns as the CLI's flags do; without
    them the columns are found from the header (docs/csv-dialects.md)."""
    return _core.read_recording(os.fspath(path), topic=topic, instance=instance,
                                time_source=time_source, lcm_channel=lcm_channel,
                                rate_hz=rate_hz, drop_non_finite=drop_non_finite,
                                threads=threads,
                                config=None if config is None else os.fspath(config),
                                time_col=time_col, time_unit=time_unit,
                                gyro_cols=list(gyro_cols), gyro_unit=gyro_unit,
                                accel_cols=list(accel_cols), accel_unit=accel_unit)


def recording_from_arrays(rate_hz: float, source: str = "arrays", **channels) -> Recording:
    """A recording sampled at exactly RATE_HZ from numpy arrays named gyro_x … gyro_z [rad/s]
    and accel_x … accel_z [m/s^2] (any subset, all of one length)."""
    return _core.recording_from_arrays(float(rate_hz), channels, source)


def simulate(model_path: Union[str, os.PathLike], duration_s: float,
             rate_hz: Optional[float] = None, seed: int = 1) -> Recording:
    """DURATION_S of the stationary IMU described by MODEL_PATH (a simulator YAML, see
    docs/simulation-model.md, or a fitted model.yaml), as `imunoise simulate` draws it."""
    return _core.simulate(os.fspath(model_path), float(duration_s), rate_hz, int(seed))


@dataclass(frozen=True)
class Estimate:
    """One coefficient of model.yaml: value, interval and whether the data showed the term
    (when not, value is 0 and ci_high an upper bound)."""
    value: float
    ci_low: float
    ci_high: float
    identified: bool
    method: str = ""
    interval_method: str = ""


_TERM_KEYS = ("quantization", "white_noise", "bias_instability", "random_walk", "ramp")


class Model:
    """A fitted noise model: the content of model.yaml (docs/model-yaml.md) as Python objects.

    ``model.data`` is the whole file as dicts and lists; ``model.axes`` maps gyro_x … accel_z
    to their axis dict; ``model.term(axis, 'white_noise')`` gives that coefficient as an
    Estimate in its SI unit (the key in model.yaml names it, e.g. white_noise_rad_per_sqrt_s)."""

    def __init__(self, yaml_text: str, source: str = "model.yaml"):
        import yaml  # Debian python3-yaml

        # Checked and normalised by the C++ reader: a bad file raises InputError here.
        self.yaml = _core.parse_model_yaml(yaml_text, source)
        self.source = source
        self.data: Dict[str, Any] = yaml.safe_load(self.yaml)

    @classmethod
    def load(cls, path: Union[str, os.PathLike]) -> "Model":
        with open(path, encoding="utf-8") as f:
            return cls(f.read(), os.fspath(path))

    @property
    def axes(self) -> Dict[str, Dict[str, Any]]:
        return self.data["axes"]

    def term_key(self, axis: str, term: str) -> str:
        """The model.yaml key of TERM (quantization, white_noise, bias_instability, random_walk,
        ramp) on AXIS, which carries the SI unit."""
        if term not in _TERM_KEYS:
            raise InputError(f"term: expected one of {', '.join(_TERM_KEYS)}, got '{term}'")
        if axis not in self.axes:
            raise InputError(f"axis: no axis '{axis}' in this model ({', '.join(self.axes)})")
        for key in self.axes[axis]:
            if key.startswith(term + "_") and not key.startswith("bias_instability_as") and \
                    not key.startswith("bias_instability_multi"):
                return key
        raise InputError(f"{self.source}: axis {axis} has no {term} term")

    def term(self, axis: str, term: str) -> Estimate:
        e = self.axes[axis][self.term_key(axis, term)]
        return Estimate(float(e["value"]), float(e["ci_low"]), float(e["ci_high"]),
                        bool(e["identified"]), e.get("method", ""), e.get("interval_method", ""))

    def write(self, path: Union[str, os.PathLike]) -> None:
        """Writes model.yaml to PATH atomically (a temporary file renamed over PATH)."""
        _write_atomically(os.fspath(path), self.yaml)


@dataclass(frozen=True)
class FitResult:
    """fit()'s result: the model and, per axis, its OADEV and OHDEV curves (tau_s, value,
    ci_low, ci_high, edf) and its PSD (frequency_hz, density, dof), as allan.csv and psd.csv."""
    model: Model
    curves: Dict[str, Dict[str, Dict[str, np.ndarray]]]
    tau0_s: float


def fit(recording: Recording, *, taus: str = "log:10", confidence: float = 0.95,
        interval_draws: int = 200, bootstrap: Optional[int] = None, seed: int = 1,
        gauss_markov: Optional[bool] = None, sinusoid_hz: Sequence[float] = (),
        tau_min_s: float = 0.0, tau_max_s: float = 0.0, low_pass_check: bool = True,
        gaps: str = "refuse", threads: int = 0) -> FitResult:
    """The noise model of every gyro/accelerometer channel of RECORDING, with the settings and
    defaults of `imunoise analyze` (the same recording and settings give the same model.yaml).
    GAUSS_MARKOV: None (default) fits the model with Gauss-Markov terms apart and keeps it
    when its penalized deviance is lower, True = `--gauss-markov`, False = `--no-gauss-markov`."""
    r = _core.fit(recording, taus=taus, confidence=float(confidence),
                  interval_draws=int(interval_draws), bootstrap=bootstrap, seed=int(seed),
                  gauss_markov=None if gauss_markov is None else bool(gauss_markov),
                  sinusoid_hz=[float(f) for f in sinusoid_hz],
                  tau_min_s=float(tau_min_s), tau_max_s=float(tau_max_s),
                  low_pass_check=bool(low_pass_check), gaps=gaps, threads=int(threads))
    return FitResult(Model(r["model_yaml"], recording.source_path), r["axes"], r["tau0_s"])


def export(model: Model, format: str, *, rate_hz: float = 0.0, axis: str = "worst",
           conservative: bool = False, gm_convention: str = "peak_match",
           correction_interval_s: float = 0.0) -> str:
    """The text of the filter config FORMAT (kalibr, openvins, vins, orbslam3, okvis, kf-gins,
    gnss-ins-sim, matlab, px4, robot_localization, native, …) for MODEL, as `imunoise export`
    writes it (docs/exports.md); the header names this call instead of a command line."""
    return _core.export_config(model.yaml, model.source, format, rate_hz=float(rate_hz),
                               axis=axis, conservative=bool(conservative),
                               gm_convention=gm_convention,
                               correction_interval_s=float(correction_interval_s))


def _write_atomically(path: str, text: str) -> None:
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", dir=folder)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
