"""Time simulation and the virtual rig: the rig's recording equals oscilab-cli simulate's sample
for sample, and the time simulation is the rig's truth."""

import numpy as np
import pytest

import oscilab
from conftest import run_cli

SHORT = {"levels_n": "0.5,1.0", "hold_s": 3.0, "lead_in_s": 0.5}


@pytest.fixture(scope="module")
def rig():
    return oscilab.virtual_rig("paper", seed=4, **SHORT)


def test_virtual_rig_recording_equals_cli_simulate(tmp_path, rig):
    cli_out = tmp_path / "cli.flac"
    result = run_cli("simulate", "--levels", "0.5,1.0", "--hold", 3, "--lead-in", 0.5,
                     "--seed", 4, "--out", cli_out)
    py_out = tmp_path / "py.flac"
    rig["recording"].write(py_out)
    cli_rec, py_rec = oscilab.read_recording(cli_out), oscilab.read_recording(py_out)
    np.testing.assert_array_equal(py_rec.samples_stored, cli_rec.samples_stored)
    assert py_rec.sidecar == cli_rec.sidecar
    # "true steady EDC per level (J): 0.0123@0.5N ..." as the CLI prints it
    printed = [f"{e:.3g}@{f:.2g}N" for f, e in zip(rig["levels"]["f0_n"], rig["levels"]["edc_j"])]
    assert " ".join(printed) in result.stdout


def test_time_simulation_is_the_rigs_truth(rig):
    sim = oscilab.simulate("paper", **SHORT)
    assert sim["status"] == "ok"
    for name in ("t_s", "z_m", "z_dot_m_s", "f_n", "restoring_force_n", "dissipated_j"):
        np.testing.assert_array_equal(sim[name], rig["truth"][name])
    np.testing.assert_array_equal(sim["levels"]["edc_j"], rig["levels"]["edc_j"])


def test_energy_balance_holds_to_the_integration_tolerance():
    model = oscilab.Model.paper()
    sim = oscilab.simulate(model, test="random", duration_s=6.0, rms_n=1.0, seed=2)
    z, v = sim["z_m"], sim["z_dot_m_s"]
    mechanical = 0.5 * model.mass_kg * v**2 + model.potential_j(z)
    balance = sim["work_in_j"] - sim["dissipated_j"] - (mechanical - mechanical[0])
    assert np.max(np.abs(balance)) < 1e-6 * np.max(np.abs(sim["work_in_j"]))  # rtol 1e-9 steps


def test_progress_and_bad_arguments():
    fractions = []
    oscilab.simulate("illustrative", levels_n=[0.5], hold_s=3.0, lead_in_s=0.0,
                     progress=lambda info: fractions.append(info["fraction"]))
    assert fractions and max(fractions) <= 1.0
    with pytest.raises(ValueError, match="levels_n: \"x\" is not a number"):
        oscilab.simulate(levels_n="0.5:x:1")
    with pytest.raises(ValueError, match="test: \"sweep\""):
        oscilab.virtual_rig(test="sweep")
    with pytest.raises(ValueError, match="well: \"up\""):
        oscilab.simulate(well="up")


def test_virtual_rig_names_its_rate_as_simulate_does_and_still_takes_the_old_name():
    short = dict(test="random", duration_s=5.0, seed=4)
    rig = oscilab.virtual_rig(sample_rate_hz=256.0, **short)
    assert rig["recording"].sample_rate_hz == 256.0
    with pytest.warns(DeprecationWarning, match="sample_rate_hz"):
        old = oscilab.virtual_rig(rate_hz=256.0, **short)
    assert old["recording"] == rig["recording"]
