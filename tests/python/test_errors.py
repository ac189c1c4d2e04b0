"""The module's exceptions: the family (oscilab.Error, InputError, FileError, MissingFileError) and
every path that raises them, paths as str, bytes and os.PathLike, arrays built in Python checked as
a file's samples are, and wrong types as TypeError naming the argument."""

import errno
import json
import os
import pathlib

import numpy as np
import pytest

import oscilab
from conftest import SAMPLES, STEPPED, cli_error


def sidecar():
    return json.loads((SAMPLES / "stepped_positive.json").read_text())


def small_samples(rows=64):
    """A few samples in SI (m/s², m): the contents do not matter to the checks."""
    t = np.arange(rows) / 512.0
    return np.column_stack([np.sin(2 * np.pi * 9 * t), 1e-3 * np.cos(2 * np.pi * 9 * t)])


# --- The family ---------------------------------------------------------------------------------


def test_the_exceptions_form_one_family_under_python_builtins():
    assert issubclass(oscilab.Error, Exception)
    assert issubclass(oscilab.InputError, oscilab.Error)
    assert issubclass(oscilab.InputError, ValueError)
    assert issubclass(oscilab.FileError, oscilab.Error)
    assert issubclass(oscilab.FileError, OSError)
    assert issubclass(oscilab.MissingFileError, oscilab.FileError)
    assert issubclass(oscilab.MissingFileError, FileNotFoundError)
    assert not issubclass(oscilab.FileError, ValueError)
    for error in (oscilab.Error, oscilab.InputError, oscilab.FileError, oscilab.MissingFileError):
        assert error.__module__ == "oscilab"
        assert error.__doc__
        assert error.__name__ in oscilab.__all__


# --- Files --------------------------------------------------------------------------------------


@pytest.mark.parametrize("as_type", [str, pathlib.Path, os.fsencode])
def test_a_missing_recording_is_a_missing_file_error_whatever_the_path_type(tmp_path, as_type):
    missing = tmp_path / "missing.flac"
    message = cli_error("info", missing)
    with pytest.raises(oscilab.MissingFileError) as error:
        oscilab.read_recording(as_type(str(missing)))
    assert str(error.value) == message  # a bytes path is not mangled into "b'...'"
    assert isinstance(error.value, FileNotFoundError)
    assert isinstance(error.value, oscilab.Error)
    assert error.value.errno == errno.ENOENT  # as open() would say


def test_bytes_and_pathlike_paths_read_the_same_recording():
    path = STEPPED[0]
    by_str = oscilab.read_recording(path)
    for other in (os.fsencode(path), pathlib.Path(path)):
        np.testing.assert_array_equal(oscilab.read_recording(other).samples, by_str.samples)
    assert oscilab.describe_recording(os.fsencode(path)) == oscilab.describe_recording(path)


def test_analyze_takes_bytes_paths_alone_and_in_sequences():
    by_str = oscilab.analyze(STEPPED)
    by_bytes = oscilab.analyze([os.fsencode(p) for p in STEPPED])
    np.testing.assert_array_equal(by_bytes.edc["edc_mean_j"], by_str.edc["edc_mean_j"])
    single = oscilab.analyze(os.fsencode(STEPPED[0]))
    assert len(single.edc["f0_n"]) > 0


def test_a_missing_model_file_is_a_missing_file_error_naming_the_argument(tmp_path):
    with pytest.raises(oscilab.MissingFileError,
                       match=r"missing\.json: file not found \(path: a model JSON file\)"):
        oscilab.Model.load(tmp_path / "missing.json")
    # A misspelt built-in name is a model file that does not exist, said with the keyword.
    with pytest.raises(FileNotFoundError) as error:
        oscilab.hbm_branch("papr")
    assert str(error.value) == ("papr: file not found (model: not 'paper', 'illustrative' or a "
                                "model JSON file)")
    with pytest.raises(oscilab.MissingFileError, match=r"spec: not 'paper'"):
        oscilab.Model.from_spec(os.fsencode(str(tmp_path / "nope.json")))


def test_a_file_the_system_refuses_is_a_file_error(tmp_path):
    rec = oscilab.read_recording(STEPPED[0])
    with pytest.raises(oscilab.FileError) as error:
        rec.write(tmp_path / "no" / "such" / "dir" / "x.wav")
    assert isinstance(error.value, OSError)
    assert "x.wav: cannot" in str(error.value)


def test_an_unreadable_recording_is_an_input_error_with_the_cli_message(tmp_path):
    (tmp_path / "x.flac").write_bytes(b"not audio")
    (tmp_path / "x.json").write_text(json.dumps(sidecar()))
    message = cli_error("info", tmp_path / "x.flac")
    with pytest.raises(oscilab.Error) as error:
        oscilab.read_recording(tmp_path / "x.flac")
    assert str(error.value) == message


def test_a_record_none_of_whose_levels_measures_anything_is_refused_as_by_the_cli(tmp_path):
    rec = oscilab.read_recording(STEPPED[0])
    side = rec.sidecar
    for channel in side["channels"]:  # the samples below are in SI
        del channel["scale"]
    samples = rec.samples.copy()
    samples[:, 0] = 0.0  # a dead accelerometer
    oscilab.Recording(side, samples).write(tmp_path / "dead.wav")
    message = cli_error("analyze", tmp_path / "dead.wav", "--edc", tmp_path / "e.csv")
    assert "no usable level: 26 of 26 levels flagged base-constant" in message
    with pytest.raises(oscilab.InputError) as error:
        oscilab.analyze(tmp_path / "dead.wav")
    assert str(error.value) == message
    assert not (tmp_path / "e.csv").exists()


# --- Keyword names instead of the CLI's options -------------------------------------------------


def test_messages_name_keyword_arguments_not_cli_options(tmp_path):
    cli_message = cli_error("fit", *STEPPED, "--method", "newton", "--out", tmp_path / "f.json")
    assert cli_message.startswith("--method: ")
    with pytest.raises(oscilab.InputError) as error:
        oscilab.fit(STEPPED, method="newton")
    assert str(error.value) == cli_message.replace("--method", "method", 1)
    with pytest.raises(oscilab.InputError, match=r"^population: must be at least 2"):
        oscilab.fit(STEPPED, population=1)
    with pytest.raises(oscilab.InputError, match=r"^well: \"left\""):
        oscilab.analyze(STEPPED, well="left")
    with pytest.raises(oscilab.InputError, match=r"^freq_hz: "):
        oscilab.analyze(STEPPED, freq_hz=-1.0)


# --- Wrong types: TypeError naming the argument, not pybind11's cast message --------------------


@pytest.mark.parametrize("call, message", [
    (lambda: oscilab.analyze(3), "recordings: expected a path, a Recording or a sequence"),
    (lambda: oscilab.fit(3.5), "recordings: expected a path, a Recording, an Analysis"),
    (lambda: oscilab.analyze(STEPPED, well=3), "well: expected a str, not int"),
    (lambda: oscilab.analyze(STEPPED, freq_hz="9"), "freq_hz: expected a number, not str"),
    (lambda: oscilab.Model.paper(ks="1"), "ks: expected a number, not str"),
    (lambda: oscilab.simulate(z0_m="0"), "z0_m: expected a number, not str"),
    (lambda: oscilab.read_recording(3), "expected str, bytes or os.PathLike object, not int"),
])
def test_wrong_types_raise_type_error_naming_the_argument(call, message):
    with pytest.raises(TypeError) as error:
        call()
    assert message in str(error.value)
    assert "PYBIND11" not in str(error.value)
    assert "C++" not in str(error.value)


# --- Arrays built in Python are checked like a file's samples -----------------------------------


def test_a_nan_sample_is_refused_naming_the_channel_and_the_sample():
    samples = small_samples()
    samples[5, 1] = np.nan
    samples[9, 1] = np.nan
    with pytest.raises(oscilab.InputError) as error:
        oscilab.Recording(sidecar(), samples)
    assert str(error.value) == ('samples: channel "y": sample 5 (t = 0.00976562 s) is NaN; '
                                "2 of 64 samples of this channel are not finite")


def test_an_infinite_sample_in_a_dict_of_columns_is_refused():
    samples = small_samples()
    columns = {"base_acc": samples[:, 0].copy(), "y": samples[:, 1]}
    columns["base_acc"][0] = -np.inf
    with pytest.raises(ValueError, match=r'^samples: channel "base_acc": sample 0 \(t = 0 s\) '
                                         r"is infinite; 1 of 64 samples"):
        oscilab.Recording(sidecar(), columns)


def test_all_nan_samples_are_refused_instead_of_analysed_to_nothing():
    with pytest.raises(oscilab.InputError, match="64 of 64 samples of this channel"):
        oscilab.Recording(sidecar(), np.full((64, 2), np.nan))


def test_nan_inside_the_sidecars_invalid_intervals_is_what_was_recorded():
    side = sidecar()
    side["invalid_intervals"] = [{"start_s": 0.0, "end_s": 0.02, "reason": "dropout"}]
    samples = small_samples()
    samples[3, :] = np.nan  # t = 5.9 ms: inside
    rec = oscilab.Recording(side, samples)
    assert np.isnan(rec.samples[3, 0])
    samples[40, 0] = np.nan  # t = 78 ms: outside
    with pytest.raises(oscilab.InputError, match=r"sample 40 "):
        oscilab.Recording(side, samples)


def test_si_samples_need_no_scale_per_channel(tmp_path):
    side = sidecar()
    for channel in side["channels"]:
        del channel["scale"]
    samples = small_samples()
    rec = oscilab.Recording(side, samples)
    np.testing.assert_array_equal(rec.samples, samples)
    assert [c["scale"] for c in rec.sidecar["channels"]] == [1.0, 1.0]
    rec.write(tmp_path / "si.wav")
    np.testing.assert_allclose(oscilab.read_recording(tmp_path / "si.wav").samples, samples,
                               rtol=1e-6, atol=1e-9)
