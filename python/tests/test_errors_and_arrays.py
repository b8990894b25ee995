"""Errors are Python exceptions with the CLI's messages; arrays are viewed without copies."""
import numpy as np
import pytest

import imunoise


def test_a_missing_file_gives_the_message_of_the_cli(imunoise_cli, tmp_path):
    missing = tmp_path / "nope.csv"
    cli = imunoise_cli("check", missing, check=False)
    assert cli.returncode == 2
    with pytest.raises(imunoise.InputError) as e:
        imunoise.read_recording(missing)
    assert isinstance(e.value, ValueError)
    assert str(e.value) in cli.stderr


def test_bad_arguments_are_input_errors():
    x = np.zeros(100)
    with pytest.raises(imunoise.InputError, match="unknown deviation 'foo'"):
        imunoise.deviation(x, "foo")
    with pytest.raises(imunoise.InputError, match="1-D"):
        imunoise.deviation(np.zeros((3, 3)))
    y = np.ones(100)
    y[17] = np.nan
    with pytest.raises(imunoise.InputError, match="value 17 is not finite"):
        imunoise.deviation(y)
    with pytest.raises(imunoise.InputError, match="rate"):
        imunoise.deviation(x, rate=-1.0)
    with pytest.raises(imunoise.InputError, match="unknown channel 'gyro_w'"):
        imunoise.recording_from_arrays(100.0, gyro_w=x)


def test_data_that_cannot_answer_is_an_analysis_error():
    with pytest.raises(imunoise.AnalysisError):
        imunoise.deviation(np.random.default_rng(1).standard_normal(10), taus=[20])


def test_recording_channels_are_views_of_its_memory():
    rng = np.random.default_rng(2)
    gyro = rng.standard_normal(5000) * 1e-3
    rec = imunoise.recording_from_arrays(100.0, gyro_x=gyro, accel_z=9.8 + gyro)
    a = rec.channel("gyro_x")
    b = rec.channel("gyro_x")
    assert np.shares_memory(a, b)  # both view the recording's buffer
    np.testing.assert_array_equal(a, gyro)
    assert rec.channel_names == ["gyro_x", "accel_z"]
    assert rec.unit("accel_z") == "m/s^2"
    del rec
    assert a.sum() == pytest.approx(gyro.sum())  # the view keeps the recording alive


def test_fit_of_arrays_recovers_white_noise():
    # White rate noise of sigma s at rate f: N = s / sqrt(f) (theory.md §1.3), to within the
    # interval; 2 h at 50 Hz.
    rng = np.random.default_rng(3)
    f, n_true = 50.0, 2e-4
    x = rng.standard_normal(int(2 * 3600 * f)) * n_true * np.sqrt(f)
    model = imunoise.fit(imunoise.recording_from_arrays(f, gyro_x=x)).model
    e = model.term("gyro_x", "white_noise")
    assert e.identified
    assert e.ci_low < n_true < e.ci_high
    assert abs(e.value / n_true - 1) < 0.01


def test_the_gil_is_released_while_the_core_computes():
    # A thread runs a long deviation; once it has entered the call, the main thread keeps
    # running Python. With the GIL held for the call, the main thread could not run at all
    # until the call returned (the count would stay at the handful of loops before it).
    import threading

    x = np.random.default_rng(4).standard_normal(4_000_000)
    entered = threading.Event()
    done = threading.Event()

    def work():
        entered.set()
        imunoise.deviation(x, "mdev", rate=100.0, taus="octave", threads=1)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    entered.wait()
    count = 0
    while not done.is_set():
        count += 1
    t.join()
    assert count > 10_000, count


def test_model_write_and_load_round_trip(tmp_path):
    # Model.write and Model.load side by side: the file read back is the same model.yaml text
    # and the same objects.
    rng = np.random.default_rng(5)
    x = rng.standard_normal(180_000) * 1e-3
    model = imunoise.fit(imunoise.recording_from_arrays(50.0, gyro_x=x), interval_draws=0).model
    model.write(tmp_path / "model.yaml")
    back = imunoise.Model.load(tmp_path / "model.yaml")
    assert back.yaml == model.yaml
    assert back.data == model.data
    assert back.term("gyro_x", "white_noise") == model.term("gyro_x", "white_noise")
    assert not list(tmp_path.glob(".tmp-*"))  # the temporary file was renamed, none left
