"""The worked example of docs/python.md runs as written: read, analyse, fit on the samples (and,
when matplotlib is installed, the plot of the measured and fitted EDC)."""

import contextlib
import importlib.util
import io
import os
import re

import pytest

from conftest import SOURCE_DIR


def example_code():
    text = (SOURCE_DIR / "docs" / "python.md").read_text()
    section = text[text.index("## A worked example"):]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


@pytest.fixture(scope="module")
def example_run():
    """The example up to its plot, run once: (its namespace, what it printed, the plot's code)."""
    code = example_code()
    plotting = code.index("import matplotlib")
    here = os.getcwd()
    os.chdir(SOURCE_DIR)  # the example names the samples relative to the repository
    printed = io.StringIO()
    namespace = {}
    try:
        with contextlib.redirect_stdout(printed):
            exec(compile(code[:plotting], "docs/python.md", "exec"), namespace)
    finally:
        os.chdir(here)
    return namespace, printed.getvalue(), code[plotting:]


def test_the_worked_example_reads_analyses_and_fits_the_samples(example_run):
    namespace, printed, _ = example_run
    fit = namespace["fit"]
    assert fit["status"] == "ok"
    assert set(fit["parameters"]) == {"fd_zminus_n", "fd_zero_n", "fd_zplus_n", "ks", "c_ns_m",
                                      "vt_m_s"}
    assert "<oscilab.Recording 2 channels" in printed
    assert " mJ" in printed


def test_the_worked_example_plots_the_edc(example_run, tmp_path, monkeypatch):
    namespace, _, plot_code = example_run
    if importlib.util.find_spec("matplotlib") is None:
        pytest.skip("the plot needs matplotlib (optional, python3-matplotlib)")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.chdir(tmp_path)
    exec(compile(plot_code, "docs/python.md", "exec"), namespace)
    assert (tmp_path / "edc.png").stat().st_size > 0
