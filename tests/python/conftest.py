"""Shared fixtures of the Python module's tests: the CLI, the samples, and each CLI result the
bindings are compared with (computed once per session)."""

import csv
import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("OSCILAB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SAMPLES = SOURCE_DIR / "samples"
STEPPED = [str(SAMPLES / "stepped_positive.flac"), str(SAMPLES / "stepped_negative.flac")]


def cli_path():
    cli = os.environ.get("OSCILAB_CLI")
    if not cli:
        pytest.fail("OSCILAB_CLI is not set: run the suite through ctest (tests/CMakeLists.txt)")
    return cli


def run_cli(*args, check=True):
    """Runs oscilab-cli; returns the CompletedProcess (text)."""
    result = subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True,
                            check=False)
    if check and result.returncode != 0:
        raise AssertionError(f"oscilab-cli {' '.join(map(str, args))} exited "
                             f"{result.returncode}: {result.stderr}")
    return result


def cli_error(*args):
    """The one line oscilab-cli prints for bad input (exit 2), without its 'oscilab-cli: '."""
    result = run_cli(*args, check=False)
    assert result.returncode == 2, (result.returncode, result.stderr)
    line = result.stderr.strip()
    assert "\n" not in line
    prefix = "oscilab-cli: "
    assert line.startswith(prefix)
    return line[len(prefix):]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_json(path):
    with open(path) as f:
        return json.load(f)


@pytest.fixture(scope="session")
def cli_analysis(tmp_path_factory):
    """oscilab-cli analyze on both stepped samples: EDC, RFS, damping, cycles, summary."""
    out = tmp_path_factory.mktemp("cli_analyze")
    run_cli("analyze", *STEPPED, "--edc", out / "edc.csv", "--rfs", out / "rfs.csv",
            "--damping", out / "damping.csv", "--cycles", out / "cycles.csv",
            "--summary", out / "summary.json")
    return {
        "edc": read_csv(out / "edc.csv"),
        "rfs": read_csv(out / "rfs.csv"),
        "damping": read_csv(out / "damping.csv"),
        "cycles": read_csv(out / "cycles.csv"),
        "summary": read_json(out / "summary.json"),
    }


@pytest.fixture(scope="session")
def py_analysis():
    import oscilab
    return oscilab.analyze(STEPPED)
