"""Harmonic balance: hbm_branch() equals oscilab-cli hbm's branch CSV (printed to 10 digits)."""

import math

import numpy as np
import pytest

import oscilab
from conftest import read_csv, run_cli

COLUMNS = ["f0_n", "amp_m", "z1_abs_m", "phase_rad", "edc_j", "stable", "freq_hz",
           "edc_dissipation_j", "mu1_abs", "mu2_abs", "mu1_re", "mu1_im", "mu2_re", "mu2_im",
           "marker", "newton_iterations"]


def cxx_print(value):
    """What an ostream with precision(10) writes for a double (the branch CSV)."""
    text = "%.10g" % value
    return text


@pytest.fixture(scope="module")
def branches(tmp_path_factory):
    out = tmp_path_factory.mktemp("hbm") / "branch.csv"
    run_cli("hbm", "--model", "paper", "--freq", 9, "--f0", "0.1:2.0", "--well", "positive",
            "--harmonics", 5, "--out", out)
    return read_csv(out), oscilab.hbm_branch("paper", freq_hz=9.0, f0_n=(0.1, 2.0),
                                             well="positive", harmonics=5)


def test_branch_equals_cli_csv(branches):
    rows, branch = branches
    assert list(rows[0].keys()) == COLUMNS
    assert len(branch["f0_n"]) == len(rows)
    for name in COLUMNS:
        for i, row in enumerate(rows):
            value = branch[name][i]
            if name in ("stable", "newton_iterations"):
                assert str(int(value)) == row[name], (name, i)
            elif name == "marker":
                assert value == row[name]
            elif math.isnan(value):
                assert row[name] == ""
            else:
                assert cxx_print(value) == row[name], (name, i, value, row[name])


def test_folds_and_stability_as_arrays(branches):
    _, branch = branches
    assert branch["status"] == "ok"
    folds = branch["folds"]
    assert len(folds["f0_n"]) == len(folds["point_index"])
    for k, i in enumerate(folds["point_index"]):
        assert branch["marker"][i] == "fold"
        assert branch["f0_n"][i] == pytest.approx(folds["f0_n"][k])
    # Stable points: every Floquet multiplier inside the unit circle.
    stable = branch["stable"] == 1
    assert np.all(branch["mu1_abs"][stable] < 1.0)
    assert branch["coefficients"].shape == (len(branch["f0_n"]), 2 * 5 + 1)
    assert branch["marker"][0] == "start" and branch["marker"][-1] == "end"


def test_bad_options_raise_value_error():
    with pytest.raises(ValueError, match="well"):
        oscilab.hbm_branch(well="left")
    with pytest.raises(ValueError):
        oscilab.hbm_branch(harmonics=0)


def assert_branch_prints_as(branch, rows):
    assert len(branch["f0_n"]) == len(rows)
    for name in COLUMNS:
        for i, row in enumerate(rows):
            value = branch[name][i]
            if name in ("stable", "newton_iterations"):
                assert str(int(value)) == row[name], (name, i)
            elif name == "marker":
                assert value == row[name]
            elif math.isnan(value):
                assert row[name] == ""
            else:
                assert cxx_print(value) == row[name], (name, i, value, row[name])


def test_period_doubled_branches_equal_cli_follow_period_doubling(tmp_path):
    out = tmp_path / "pd.csv"
    run_cli("hbm", "--f0", "3.0:3.7", "--well", "positive", "--follow-period-doubling",
            "--out", out)
    rows = read_csv(out)
    branch = oscilab.hbm_branch("paper", f0_n=(3.0, 3.7), follow_period_doubling=True)
    assert len(branch["period_doublings"]["f0_n"]) >= 1
    assert_branch_prints_as(branch, [r for r in rows if r["period"] == "1"])
    followed = [b for b in branch["period_doubled"] if len(b["f0_n"]) > 0]
    assert followed and followed[0]["period"] == 2
    assert followed[0]["f0_pitchfork_n"] < followed[0]["f0_flip_n"]
    for b in followed:
        assert_branch_prints_as(b, [r for r in rows if r["period"] == str(b["period"])])
    with pytest.raises(ValueError, match="follow_period_doubling"):
        oscilab.hbm_branch(follow_period_doubling=True, stability=False)


def test_bifurcation_map_equals_the_clis_map_csv_for_both_wells(tmp_path):
    run_cli("hbm", "--model", "paper", "--freq", 9, "--f0", "1.0:1.2", "--well", "both",
            "--out", tmp_path / "branch.csv", "--map", tmp_path / "map.csv", "--map-step", 0.1,
            "--map-hold", 30, "--map-sampled", 4)
    rows = read_csv(tmp_path / "map.csv")
    result = oscilab.bifurcation_map(f0_n=(1.0, 1.2), step_n=0.1, well="both", hold_periods=30,
                                     sampled_periods=4)
    assert result["status"] == "ok"
    python = result["rows"]
    assert len(python["z_m"]) == len(rows) == 2 * 3 * 4  # wells × levels × sections
    assert python["well"] == [r["well"] for r in rows]
    assert list(python["period"]) == [int(r["period"]) for r in rows]
    np.testing.assert_allclose(python["f0_n"], [float(r["f0_n"]) for r in rows], rtol=1e-9)
    # The CSV holds 10 significant digits.
    np.testing.assert_allclose(python["z_m"], [float(r["z_m"]) for r in rows], rtol=1e-9)
    levels = result["levels"]
    assert levels["well"] == ["positive"] * 3 + ["negative"] * 3
    assert list(levels["distinct_points"]) == [1] * 6  # period 1 at these levels
    with pytest.raises(oscilab.InputError, match="well"):
        oscilab.bifurcation_map(well="left")


def test_amplitude_sweep_equals_the_clis_sweep_csv(tmp_path):
    run_cli("hbm", "--model", "paper", "--freq", 9, "--f0", "0.1:1.0", "--well", "positive",
            "--out", tmp_path / "branch.csv", "--sweep", tmp_path / "sweep.csv",
            "--sweep-time", 10)
    rows = read_csv(tmp_path / "sweep.csv")
    sweep = oscilab.amplitude_sweep(f0_max_n=1.0, up_s=10.0, well="positive")
    assert sweep["status"] == "ok"
    assert len(sweep["f0_n"]) == len(rows) == 2 * 10 * 9  # both ways, 10 s at 9 Hz each
    assert sweep["direction"] == [r["direction"] for r in rows]
    for column in ("f0_n", "amp_m", "t_s"):  # the CSV holds 10 significant digits
        np.testing.assert_allclose(sweep[column], [float(r[column]) for r in rows], rtol=1e-9,
                                   atol=1e-15, err_msg=column)
    assert sweep["jump_up"]["f0_n"] > sweep["jump_down"]["f0_n"]  # hysteresis
    with pytest.raises(oscilab.InputError):
        oscilab.amplitude_sweep(f0_max_n=-1.0)


def test_hbm_branch_of_both_wells_is_one_branch_per_well():
    both = oscilab.hbm_branch(f0_n=(0.1, 1.0), well="both")
    assert list(both) == ["positive", "negative"]
    for well in ("positive", "negative"):
        alone = oscilab.hbm_branch(f0_n=(0.1, 1.0), well=well)
        assert both[well]["well"] == alone["well"]
        np.testing.assert_array_equal(both[well]["f0_n"], alone["f0_n"])
        np.testing.assert_array_equal(both[well]["amp_m"], alone["amp_m"])
