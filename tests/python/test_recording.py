"""Recordings: read (any format), describe (= oscilab-cli info), build from arrays, write."""

import json

import numpy as np
import pytest

import oscilab
from conftest import SAMPLES, cli_error, run_cli


def test_read_recording_gives_si_channels_and_sidecar_of_the_sample():
    rec = oscilab.read_recording(SAMPLES / "stepped_positive.flac")
    sidecar = json.loads((SAMPLES / "stepped_positive.json").read_text())
    assert rec.sample_rate_hz == sidecar["sample_rate_hz"]
    assert rec.mass_kg == sidecar["mass_kg"]
    assert rec.channel_names == [c["name"] for c in sidecar["channels"]]
    assert rec.samples.shape == (rec.sample_count, len(sidecar["channels"]))
    assert rec.duration_s == pytest.approx(rec.sample_count / rec.sample_rate_hz)
    # SI = scale × stored + offset (units m/s² and m: factor 1), exactly as the reader computes.
    for i, channel in enumerate(sidecar["channels"]):
        expected = channel["scale"] * rec.samples_stored[:, i] + channel.get("offset", 0.0)
        np.testing.assert_allclose(rec.samples[:, i], expected, rtol=1e-15, atol=0)
        np.testing.assert_array_equal(rec[channel["name"]], rec.samples[:, i])
    np.testing.assert_array_equal(rec.channel_by_role("base"), rec.samples[:, 0])
    assert rec.t_s[1] == 1.0 / rec.sample_rate_hz


def test_describe_recording_is_the_text_of_cli_info():
    path = SAMPLES / "stepped_negative.flac"
    assert oscilab.describe_recording(path) == run_cli("info", path).stdout
    assert oscilab.read_recording(path).describe() == run_cli("info", path).stdout


@pytest.mark.parametrize("extension", ["wav", "csv", "flac"])
def test_recording_built_from_arrays_round_trips_through_a_file(tmp_path, extension):
    rate = 512.0
    t = np.arange(2048) / rate
    base = 3.0 * np.sin(2 * np.pi * 9.0 * t)          # m/s²
    y = 0.02 + 1e-3 * np.sin(2 * np.pi * 9.0 * t)      # m
    sidecar = {
        "format": "oscilab-recording/1", "sample_rate_hz": rate, "mass_kg": 0.26,
        "channels": [
            {"name": "base_acc", "role": "base", "quantity": "acceleration", "unit": "m/s^2",
             "scale": 1e-4 if extension == "flac" else 1.0, "offset": 0.0},
            {"name": "y", "role": "mass", "quantity": "displacement", "unit": "m",
             "scale": 1e-7 if extension == "flac" else 1.0, "offset": 0.0},
        ],
    }
    rec = oscilab.Recording(sidecar, {"base_acc": base, "y": y})
    path = tmp_path / f"made.{extension}"
    oscilab.write_recording(rec, path)
    back = oscilab.read_recording(path)
    assert back.channel_names == ["base_acc", "y"]
    assert back.mass_kg == 0.26
    if extension == "flac":  # integer container: to half the channel's scale
        np.testing.assert_allclose(back["base_acc"], base, rtol=0, atol=0.5e-4 * 1.0001)
        np.testing.assert_allclose(back["y"], y, rtol=0, atol=0.5e-7 * 1.0001)
    else:
        # To the rounding of the calibration (stored = (SI − offset) / scale and back).
        np.testing.assert_allclose(back.samples, np.column_stack([base, y]), rtol=1e-15,
                                   atol=1e-18)
    # The CLI reads what the module wrote.
    assert "base_acc" in run_cli("info", path).stdout


def test_recording_from_a_2d_array_equals_one_from_a_dict():
    sidecar = json.loads((SAMPLES / "stepped_positive.json").read_text())
    data = np.arange(20.0).reshape(10, 2)
    a = oscilab.Recording(sidecar, data)
    b = oscilab.Recording(sidecar, {c["name"]: data[:, i] for i, c in enumerate(sidecar["channels"])})
    np.testing.assert_array_equal(a.samples, b.samples)
    assert a.samples_stored is None and a.source_path == ""


def test_missing_file_raises_file_not_found_with_the_cli_message(tmp_path):
    missing = tmp_path / "missing.flac"
    message = cli_error("info", missing)
    with pytest.raises(FileNotFoundError) as error:
        oscilab.read_recording(missing)
    assert str(error.value) == message
    assert isinstance(error.value, OSError)


def test_bad_sidecar_unit_raises_value_error_with_the_cli_message(tmp_path):
    sidecar = json.loads((SAMPLES / "stepped_positive.json").read_text())
    sidecar["channels"][1]["unit"] = "mps"
    (tmp_path / "bad.json").write_text(json.dumps(sidecar))
    (tmp_path / "bad.flac").write_bytes((SAMPLES / "stepped_positive.flac").read_bytes())
    message = cli_error("info", tmp_path / "bad.flac")
    assert "unknown unit" in message
    with pytest.raises(ValueError) as error:
        oscilab.read_recording(tmp_path / "bad.flac")
    assert str(error.value) == message


def test_building_with_wrong_columns_or_sidecar_raises_value_error():
    sidecar = json.loads((SAMPLES / "stepped_positive.json").read_text())
    with pytest.raises(ValueError, match="3 columns for 2 sidecar channels"):
        oscilab.Recording(sidecar, np.zeros((4, 3)))
    with pytest.raises(ValueError, match="no array for the sidecar's channel"):
        oscilab.Recording(sidecar, {"base_acc": np.zeros(4)})
    del sidecar["sample_rate_hz"]
    with pytest.raises(ValueError, match="^sidecar: "):
        oscilab.Recording(sidecar, np.zeros((4, 2)))


def test_writing_into_a_missing_directory_raises_os_error(tmp_path):
    rec = oscilab.read_recording(SAMPLES / "stepped_positive.flac")
    with pytest.raises(OSError):
        rec.write(tmp_path / "no" / "such" / "dir" / "x.wav")
