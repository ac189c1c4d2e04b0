"""analyze(): the EDC table, RFS slices, stiffness fit, cycles and summary equal oscilab-cli
analyze's on the samples, to the last printed digit (the same code runs)."""

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

import oscilab
from conftest import STEPPED, cli_error, read_csv, run_cli

EDC_FORMATS = {
    "well": "%s", "f0_n": "%.6g", "edc_mean_j": "%.9g", "edc_std_j": "%.6g", "cycles": "%d",
    "record": "%s", "edc_noise_floor_j": "%.6g", "edc_eq13_mean_j": "%.9g",
    "edc_trapz_mean_j": "%.9g", "z1_abs_m": "%.9g", "lag_rad": "%.9g", "z_mean_m": "%.9g",
    "start_s": "%.6f", "end_s": "%.6f", "transient_cycles": "%d", "period1_change": "%.6g",
    "usable": "%d", "flags": "%s",
}
CYCLE_FORMATS = {
    "record": "%s", "start_s": "%.6f", "end_s": "%.6f", "f0_n": "%.6g", "edc_j": "%.9g",
    "edc_eq13_j": "%.9g", "edc_trapz_j": "%.9g", "z1_abs_m": "%.9g", "lag_rad": "%.9g",
    "z_mean_m": "%.9g", "z_min_m": "%.9g", "z_max_m": "%.9g",
}


def assert_table_prints_as(table, rows, formats):
    """Every column of `table` printed with the CLI's format equals the CLI's CSV field."""
    assert list(rows[0].keys()) == list(formats.keys())
    for name, fmt in formats.items():
        column = table[name]
        assert len(column) == len(rows), name
        for i, row in enumerate(rows):
            value = column[i]
            if fmt == "%d":
                value = int(value)
            assert fmt % value == row[name], (name, i, value, row[name])


def json_form(value):
    """A Python result as JSON would carry it: NaN and infinities become null."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: json_form(v) for k, v in value.items()}
    if isinstance(value, list):
        return [json_form(v) for v in value]
    return value


def test_edc_table_equals_cli_csv(cli_analysis, py_analysis):
    assert list(py_analysis.edc.keys())[:5] == ["well", "f0_n", "edc_mean_j", "edc_std_j",
                                                 "cycles"]
    assert_table_prints_as(py_analysis.edc, cli_analysis["edc"], EDC_FORMATS)


def test_cycles_equal_cli_csv(cli_analysis, py_analysis):
    assert_table_prints_as(py_analysis.cycles, cli_analysis["cycles"], CYCLE_FORMATS)


NON_REAL_DTYPES = {"cycles": np.int64, "transient_cycles": np.int64, "usable": np.bool_}
TEXT_COLUMNS = {"well", "record", "flags"}


@pytest.mark.parametrize("table", ["edc", "cycles"])
def test_tables_are_numpy_arrays_of_their_kinds_dtypes(py_analysis, table):
    columns = getattr(py_analysis, table)
    for name, column in columns.items():
        assert isinstance(column, np.ndarray) and column.ndim == 1, name
        if name in TEXT_COLUMNS:
            assert column.dtype.kind == "U", (name, column.dtype)  # <U…, as wide as the longest
            assert column.dtype.itemsize == 4 * max(1, max(len(str(v)) for v in column))
        else:
            assert column.dtype == NON_REAL_DTYPES.get(name, np.float64), (name, column.dtype)


def test_a_record_without_mass_and_a_level_past_its_end_gives_the_clis_table(tmp_path):
    # No mass_kg: every level flagged per-unit-mass; a sidecar level past the record's end: a
    # row without cycles, not usable.
    sidecar = json.loads(Path(STEPPED[0][:-5] + ".json").read_text())
    del sidecar["mass_kg"]
    sidecar["excitation"]["levels"].append({"f0_n": 3.0, "start_s": 300.0, "end_s": 310.0})
    (tmp_path / "nomass.json").write_text(json.dumps(sidecar))
    shutil.copy(STEPPED[0], tmp_path / "nomass.flac")
    run_cli("analyze", tmp_path / "nomass.flac", "--edc", tmp_path / "edc.csv")
    edc = oscilab.analyze(tmp_path / "nomass.flac").edc
    assert_table_prints_as(edc, read_csv(tmp_path / "edc.csv"), EDC_FORMATS)
    assert all(flags.endswith("per-unit-mass") for flags in edc["flags"])
    assert edc["flags"][-1] == "few-cycles;beyond-record;per-unit-mass"
    assert edc["well"][-1] == "" and edc["cycles"][-1] == 0
    # docs/contracts.md §3: no steady cycle, not period-1, crossing wells and the degenerate-data
    # flags make a level unusable; few-cycles and per-unit-mass alone do not.
    unusable = {"not-period-1", "cross-well", "base-constant", "mass-constant", "negative-edc",
                "non-finite"}
    expected = [bool(cycles > 0) and not unusable & set(flags.split(";"))
                for cycles, flags in zip(edc["cycles"], edc["flags"])]
    assert edc["usable"].tolist() == expected
    assert edc["usable"].sum() == len(expected) - 1


def test_stiffness_slice_and_damping_slices_equal_cli_csv(cli_analysis, py_analysis):
    assert_table_prints_as(py_analysis.rfs, cli_analysis["rfs"],
                           {"z_m": "%.9g", "restoring_force_n": "%.9g", "samples": "%d"})
    assert_table_prints_as(py_analysis.damping, cli_analysis["damping"],
                           {"z_center_m": "%.9g", "z_dot_m_s": "%.9g",
                            "damping_force_n": "%.9g", "samples": "%d"})


def test_summary_and_stiffness_fit_equal_cli_json_exactly(cli_analysis, py_analysis):
    assert json_form(py_analysis.summary) == cli_analysis["summary"]
    fit = py_analysis.stiffness_fit
    assert fit == cli_analysis["summary"]["stiffness_fit"]
    for key in ("k3_n_m3", "k2_n_m2", "k1_n_m", "k0_n"):
        assert key in fit and key + "_std" in fit


def test_analysis_of_recordings_in_memory_equals_analysis_of_files(py_analysis):
    recordings = [oscilab.read_recording(p) for p in STEPPED]
    again = oscilab.analyze(recordings)
    assert list(again.edc) == list(py_analysis.edc)
    for name, column in py_analysis.edc.items():
        np.testing.assert_array_equal(again.edc[name], column, err_msg=name)


def test_records_and_motion_describe_each_record(py_analysis):
    records = py_analysis.records
    assert [r["name"] for r in records] == ["stepped_positive.flac", "stepped_negative.flac"]
    assert all(r["stepped_sine"] and r["excitation_freq_hz"] == 9.0 for r in records)
    motion = py_analysis.motion(1)
    assert motion["t_s"].shape == motion["z_m"].shape == motion["restoring_force_n"].shape
    assert np.nanmean(motion["z_m"]) < 0  # the negative well's record stays around z₋* < 0
    with pytest.raises(ValueError, match="record: 2 is not in 0..1"):
        py_analysis.motion(2)


def test_edc_dataframe_needs_pandas_and_the_dict_form_works_without(py_analysis):
    try:
        import pandas  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pandas"):
            py_analysis.edc_dataframe()
    else:
        frame = py_analysis.edc_dataframe()
        assert list(frame.columns) == list(py_analysis.edc.keys())
        assert len(frame) == len(py_analysis.edc["f0_n"])


def test_progress_reports_fractions_and_false_cancels():
    seen = []
    result = oscilab.analyze(STEPPED[0], progress=lambda info: seen.append(info["fraction"]))
    assert result.status == "ok"
    assert all(0.0 <= f <= 1.0 for f in seen)
    # Six records on at most two threads: the first report comes when one record is done, and
    # False then stops the others between chunks of samples, long before their end.
    calls = []

    def stop(info):
        calls.append(info["fraction"])
        return False

    cancelled = oscilab.analyze(STEPPED * 3, progress=stop)
    assert cancelled.status == "cancelled"
    assert calls and calls[0] < 1.0


def test_bad_options_raise_value_error_like_the_cli():
    with pytest.raises(ValueError, match="well: \"left\" is not positive or negative"):
        oscilab.analyze(STEPPED, well="left")
    with pytest.raises(ValueError, match="freq_hz: .* is not a positive number"):
        oscilab.analyze(STEPPED, freq_hz=-1.0)
    with pytest.raises(ValueError, match="no recordings given"):
        oscilab.analyze([])


def test_unreadable_recording_raises_the_cli_message(tmp_path):
    (tmp_path / "x.flac").write_bytes(b"not audio")
    (tmp_path / "x.json").write_text((STEPPED and open(STEPPED[0][:-5] + ".json").read()))
    message = cli_error("analyze", tmp_path / "x.flac", "--edc", tmp_path / "e.csv")
    with pytest.raises((ValueError, OSError)) as error:
        oscilab.analyze(tmp_path / "x.flac")
    assert str(error.value) == message
