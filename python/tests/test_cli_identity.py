"""The same data through Python and through the CLI give bit-identical results: the allan
curve, the fitted model.yaml, the sampling report and the export texts."""
import csv
import json

import numpy as np
import pytest

import imunoise
from conftest import SOURCE_DIR

MODEL = SOURCE_DIR / "configs" / "reference-imu.yaml"


@pytest.fixture(scope="module")
def recording_csv(tmp_path_factory):
    return tmp_path_factory.mktemp("identity") / "rec.csv"


def simulate_csv(cli, path, duration="20min", rate=100, seed=3):
    cli("simulate", MODEL, "--duration", duration, "--rate", rate, "--seed", seed, "-o", path,
        "--quiet")


def test_deviation_equals_the_allan_command(imunoise_cli, tmp_path):
    path = tmp_path / "rec.csv"
    simulate_csv(imunoise_cli, path)
    for kind in ("oadev", "mdev", "ohdev", "totdev"):
        out = imunoise_cli("allan", path, "--column", "gyro_z_rad_per_s", "--type", kind, "--taus",
                           "octave", "--json").stdout
        cli = json.loads(out)
        rec = imunoise.read_recording(path)
        dev = imunoise.deviation(rec.channel("gyro_z"), kind, tau0_s=rec.sample_period_s,
                                 taus="octave", confidence=cli["confidence"])
        points = cli["points"]
        assert [p["m"] for p in points] == list(dev.m)
        # json reads back the shortest round-trip text: the same double, bit for bit.
        assert [p["value"] for p in points] == list(dev.value), kind
        assert [p["ci_low"] for p in points] == list(dev.ci_low), kind
        assert [p["ci_high"] for p in points] == list(dev.ci_high), kind


def test_fit_gives_the_model_yaml_of_analyze(imunoise_cli, tmp_path):
    path = tmp_path / "rec.csv"
    simulate_csv(imunoise_cli, path)
    imunoise_cli("analyze", path, "-o", tmp_path / "out", "--quiet")
    cli_yaml = (tmp_path / "out" / "model.yaml").read_text()
    result = imunoise.fit(imunoise.read_recording(path))
    assert result.model.yaml == cli_yaml
    # The curves behind allan.csv, bit for bit (shortest round-trip text in the file).
    rows = list(csv.DictReader(open(tmp_path / "out" / "allan.csv")))
    for axis in ("gyro_x", "accel_z"):
        curve = result.curves[axis]["oadev"]
        assert [float(r["tau_s"]) for r in rows] == list(curve["tau_s"])
        assert [float(r[f"{axis}_oadev_{'rad_per_s' if axis[0] == 'g' else 'm_per_s2'}"])
                for r in rows] == list(curve["value"])
    # The sampling report of the read is the file analyze wrote.
    rec = imunoise.read_recording(path)
    assert json.loads(rec.sampling_report_json) == \
        json.loads((tmp_path / "out" / "sampling_report.json").read_text())
    # Exports: the same text but the header line naming the command.
    model = imunoise.Model.load(tmp_path / "out" / "model.yaml")
    for fmt in ("openvins", "vins", "px4", "kf-gins", "matlab"):
        cli_text = imunoise_cli("export", tmp_path / "out" / "model.yaml", "--to", fmt).stdout
        py_text = imunoise.export(model, fmt)
        strip = lambda t: [l for l in t.splitlines() if "imunoise export" not in l
                           and "imunoise.export(" not in l]
        assert strip(py_text) == strip(cli_text), fmt


def test_simulate_gives_the_samples_of_the_simulate_command(imunoise_cli, tmp_path):
    path = tmp_path / "sim.imnb"
    imunoise_cli("simulate", MODEL, "--duration", "60s", "--rate", 200, "--seed", 5, "-o", path,
                 "--quiet")
    from_file = imunoise.read_recording(path)
    drawn = imunoise.simulate(MODEL, 60.0, rate_hz=200.0, seed=5)
    assert drawn.sample_count == from_file.sample_count == 12000
    for name in from_file.channel_names:
        np.testing.assert_array_equal(drawn.channel(name), from_file.channel(name))


def test_column_and_unit_arguments_map_a_table_as_the_cli_flags(imunoise_cli, tmp_path):
    # A headerless table in deg/s and g with the time in ms: the mapping arguments of
    # read_recording give the recording the CLI's flags give (its sampling report, and the
    # values in SI: deg/s × π/180, g × 9.80665).
    rng = np.random.default_rng(7)
    rows = 2000
    t_ms = np.arange(rows) * 5.0
    gyro = rng.standard_normal((rows, 3))
    accel = rng.standard_normal((rows, 3)) * 0.01 + [0, 0, 1]
    path = tmp_path / "plain.csv"
    with open(path, "w") as f:
        for i in range(rows):
            f.write(",".join(repr(v) for v in [t_ms[i], *gyro[i], *accel[i]]) + "\n")
    flags = ["--time-col", "1", "--time-unit", "ms", "--gyro-cols", "2,3,4", "--gyro-unit",
             "deg/s", "--accel-cols", "5,6,7", "--accel-unit", "g"]
    cli = json.loads(imunoise_cli("check", path, *flags, "--json").stdout)
    rec = imunoise.read_recording(path, time_col="1", time_unit="ms", gyro_cols=["2", "3", "4"],
                                  gyro_unit="deg/s", accel_cols=["5", "6", "7"], accel_unit="g")
    assert json.loads(rec.sampling_report_json) == cli
    np.testing.assert_allclose(rec.channel("gyro_y"), gyro[:, 1] * np.pi / 180, rtol=1e-15)
    np.testing.assert_allclose(rec.channel("accel_z"), accel[:, 2] * 9.80665, rtol=1e-15)
    with pytest.raises(imunoise.InputError, match="gyro_unit: expected"):
        imunoise.read_recording(path, gyro_unit="furlong/s")
