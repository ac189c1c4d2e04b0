"""The live chain as an iterator: a replay, the virtual rig and a network listener give the
blocks and the live EDC of oscilab-cli record."""

import subprocess

import numpy as np
import pytest

import oscilab
from conftest import STEPPED, cli_path, read_csv, run_cli

LIVE_EDC = {"well": "%s", "f0_n": "%.9g", "edc_mean_j": "%.9g", "edc_std_j": "%.9g",
            "cycles": "%d", "flags": "%s"}


def drain(session):
    """Every update until the final one; the blocks joined, the levels in order."""
    updates = list(session)
    assert updates and updates[-1]["final"]
    blocks = {k: np.concatenate([u["block"][k] for u in updates]) for k in ("t_s", "base", "mass")}
    levels = {k: [] for k in LIVE_EDC}
    for u in updates:
        for k in LIVE_EDC:
            levels[k].extend(list(u["levels"][k]))
    return updates, blocks, levels


def assert_levels_print_as(levels, rows):
    assert len(levels["f0_n"]) == len(rows)
    for name, fmt in LIVE_EDC.items():
        for value, row in zip(levels[name], rows):
            assert fmt % (int(value) if fmt == "%d" else value) == row[name], name


def test_replay_gives_every_sample_and_the_cli_live_edc(tmp_path):
    run_cli("record", "--source", "file:" + STEPPED[0], "--speed", 0, "--out",
            tmp_path / "rec.wav", "--edc", tmp_path / "live.csv")
    with oscilab.live(STEPPED[0], speed=0, poll_s=0.05) as session:
        updates, blocks, levels = drain(session)
    assert_levels_print_as(levels, read_csv(tmp_path / "live.csv"))
    recording = oscilab.read_recording(STEPPED[0])
    assert len(blocks["t_s"]) == recording.sample_count
    np.testing.assert_array_equal(blocks["t_s"], recording.t_s)
    np.testing.assert_allclose(blocks["base"], recording["base_acc"], rtol=1e-12, atol=0)
    np.testing.assert_allclose(blocks["mass"], recording["y"], rtol=1e-12, atol=0)
    assert updates[-1]["status"]["gaps"] == 0
    # The same levels as the offline analysis of the same file.
    offline = oscilab.analyze(STEPPED[0]).edc
    np.testing.assert_allclose(levels["edc_mean_j"], offline["edc_mean_j"], rtol=1e-9)


def test_virtual_rig_stepped_sine_equals_cli_record(tmp_path):
    options = ["--levels", "0.5:0.5:1.0", "--hold", 3, "--lead-in", 0.5, "--seed", 2]
    run_cli("record", "--source", "rig", "--speed", 0, "--duration", 7, *options,
            "--out", tmp_path / "rig.wav", "--edc", tmp_path / "rig.csv")
    session = oscilab.live("rig", speed=0, duration_s=7, levels_n="0.5:0.5:1.0", hold_s=3,
                           lead_in_s=0.5, seed=2, poll_s=0.05, record_to=tmp_path / "py.wav")
    updates, blocks, levels = drain(session)
    assert_levels_print_as(levels, read_csv(tmp_path / "rig.csv"))
    assert len(levels["f0_n"]) >= 1
    np.testing.assert_array_equal(np.diff(blocks["t_s"]) > 0, True)
    assert oscilab.read_recording(tmp_path / "py.wav").sample_count >= 7 * 512


def test_network_listener_receives_a_stream(tmp_path):
    session = oscilab.live("net:127.0.0.1:0", poll_s=0.05)
    session.start()
    port = session.port
    assert port and port > 0
    sender = subprocess.Popen([cli_path(), "stream", STEPPED[1], "--to", f"127.0.0.1:{port}",
                               "--speed", "0"], stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True)
    try:
        updates, blocks, levels = drain(session)
    finally:
        sender.wait(timeout=60)
    assert sender.returncode == 0, sender.stderr.read()
    assert len(blocks["t_s"]) == oscilab.read_recording(STEPPED[1]).sample_count
    offline = oscilab.analyze(STEPPED[1]).edc
    np.testing.assert_allclose(levels["edc_mean_j"], offline["edc_mean_j"], rtol=1e-9)


def test_live_errors():
    with pytest.raises(FileNotFoundError):
        oscilab.live("file:/no/such/recording.flac")
    with pytest.raises(ValueError, match="source"):
        oscilab.live("net:127.0.0.1")
    # JACK comes through the same source factory as the CLI's record --source jack:...
    with pytest.raises(ValueError, match="source jack:system:capture_1,: port 2 is empty"):
        oscilab.live("jack:system:capture_1,")
    with pytest.raises(ValueError, match="a JACK source needs its calibration"):
        oscilab.live("jack:system:capture_1,system:capture_2")
    with pytest.raises(ValueError, match="calibration"):
        oscilab.live("jack:system:capture_1,system:capture_2", calibration={"channels": 3})
    session = oscilab.live(STEPPED[0], speed=0)
    with pytest.raises(ValueError, match="only the virtual rig"):
        session.set_excitation(1.0)
    session.stop()
