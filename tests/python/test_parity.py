"""What the CLI does with a recording, from Python: MATLAB and UFF 58 export (equal to `oscilab-cli
export`) and a drafted sidecar for another program's file (equal to `info --draft-sidecar`)."""

import json
import re
import shutil

import numpy as np
import pytest

import oscilab
from conftest import STEPPED, run_cli

scipy_io = pytest.importorskip("scipy.io")

# UFF ID line 3 holds the creation date and time ("DD-MMM-YY HH:MM:SS", the month in capitals:
# "28-NOV-26 14:35:09"), which differs by run.
UFF_DATE = re.compile(r"\d\d-[A-Z]{3}-\d\d \d\d:\d\d:\d\d")


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    out = tmp_path_factory.mktemp("export")
    run_cli("export", STEPPED[0], "--mat", out / "cli.mat", "--uff", out / "cli.uff")
    rec = oscilab.read_recording(STEPPED[0])
    rec.export_mat(out / "py.mat")
    rec.export_uff(str(out / "py.uff").encode())
    return out


def test_mat_export_equals_the_clis(exported):
    cli = scipy_io.loadmat(exported / "cli.mat")
    python = scipy_io.loadmat(exported / "py.mat")
    names = {k for k in cli if not k.startswith("__")}
    assert names == {k for k in python if not k.startswith("__")}
    assert {"t_s", "base_acc", "y", "sample_rate_hz", "sidecar_json"} <= names
    for name in names:
        np.testing.assert_array_equal(python[name], cli[name], err_msg=name)


def test_uff_export_equals_the_clis_but_for_its_date(exported):
    cli = UFF_DATE.sub("DATE", (exported / "cli.uff").read_text()).splitlines()
    python = UFF_DATE.sub("DATE", (exported / "py.uff").read_text()).splitlines()
    assert python == cli


def test_uff_export_refuses_a_nan_sample(tmp_path):
    rec = oscilab.read_recording(STEPPED[0])
    sidecar = rec.sidecar
    sidecar["invalid_intervals"] = [{"start_s": 0.0, "end_s": 0.01}]
    samples = np.array(rec.samples)
    samples[1, 0] = np.nan
    with pytest.raises(oscilab.InputError, match="base_acc"):
        oscilab.Recording(sidecar, samples).export_uff(tmp_path / "gap.uff")


def test_a_drafted_sidecar_equals_the_clis_and_reads_the_file(exported, tmp_path):
    foreign = tmp_path / "foreign.uff"  # another program's file: no sidecar beside it
    shutil.copy(exported / "py.uff", foreign)
    run_cli("info", foreign, "--draft-sidecar", tmp_path / "cli_draft.json")
    cli = json.loads((tmp_path / "cli_draft.json").read_text())
    draft = oscilab.draft_sidecar(foreign)
    assert draft["sidecar"] == cli
    assert list(draft["sidecar"]) == list(cli)  # the sidecar's key order
    assert draft["complete"] is True
    assert any(note.startswith("channels[0].role: base") for note in draft["notes"])
    rec = oscilab.read_recording(foreign, sidecar=draft["sidecar"])
    original = oscilab.read_recording(STEPPED[0])
    np.testing.assert_allclose(rec.samples, original.samples, rtol=1e-11, atol=0)


def test_drafting_a_missing_file_is_a_missing_file_error(tmp_path):
    with pytest.raises(oscilab.MissingFileError):
        oscilab.draft_sidecar(tmp_path / "nothing.tdms")


def test_edc_mat_export_equals_the_clis(tmp_path):
    run_cli("export", *STEPPED, "--edc-mat", tmp_path / "cli_edc.mat")
    oscilab.analyze(STEPPED).export_edc_mat(tmp_path / "py_edc.mat")
    cli = scipy_io.loadmat(tmp_path / "cli_edc.mat")
    python = scipy_io.loadmat(tmp_path / "py_edc.mat")
    names = {k for k in cli if not k.startswith("__")}
    assert {"well", "f0_n", "edc_mean_j", "edc_std_j", "cycles", "usable"} <= names
    assert names == {k for k in python if not k.startswith("__")}
    for name in names:
        assert python[name].shape == cli[name].shape, name
        if python[name].dtype == object:
            assert [str(x) for x in python[name].ravel()] == [str(x) for x in cli[name].ravel()]
        else:
            np.testing.assert_array_equal(python[name], cli[name], err_msg=name)
