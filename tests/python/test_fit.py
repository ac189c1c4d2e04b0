"""fit(), prepare_fit() and diagnose(): the CLI's FIT JSON and report.json from the same code,
progress and cancellation, Ctrl-C (KeyboardInterrupt once the fit stopped) and the GIL released
while C++ works."""

import contextlib
import csv
import json
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import oscilab
from conftest import SAMPLES, STEPPED, cli_error, cli_path, read_json, run_cli

GA = {"method": "ga", "population": 8, "generations": 2, "seed": 3, "threads": 1}
# A fixed 5 % model-error floor instead of the σ budget's calibration (harmonic balance up to
# H = 63), which would take most of the suite's time; the budget is the same code either way.
COST = {"model_error": 0.05}
# Keys that hold wall-clock time, which two runs never share.
TIMING_KEYS = {"seconds", "robust_refit_seconds"}


def without_timing(value):
    if isinstance(value, dict):
        return {k: without_timing(v) for k, v in value.items() if k not in TIMING_KEYS}
    if isinstance(value, list):
        return [without_timing(v) for v in value]
    return value


@pytest.fixture(scope="module")
def cli_fit(tmp_path_factory):
    out = tmp_path_factory.mktemp("fit") / "fit.json"
    run_cli("fit", *STEPPED, "--method", "ga", "--population", 8, "--generations", 2,
            "--seed", 3, "--threads", 1, "--model-error", 0.05, "--out", out)
    return read_json(out)


@pytest.fixture(scope="module")
def problem(py_analysis):
    return oscilab.prepare_fit(py_analysis, **COST)


def test_fit_json_equals_cli_fit_json(cli_fit):
    result = oscilab.fit(STEPPED, **GA, **COST)
    for key in ("parameters", "cost_j", "mean_deviation_pct", "evaluations", "seconds"):
        assert key in result
    assert without_timing(result) == without_timing(cli_fit)


def test_fit_of_a_prepared_analysis_equals_fit_of_the_paths(cli_fit, problem):
    result = problem.fit(**GA)
    assert result["parameters"] == cli_fit["parameters"]
    assert result["cost_j"] == cli_fit["cost_j"]
    assert result["records"] == ["stepped_positive.flac", "stepped_negative.flac"]
    for key in ("parameters", "standard_errors", "intervals_95"):  # θ's order, not sorted
        assert list(result[key]) == problem.names, key


def test_evaluate_at_the_cli_parameters_gives_the_cli_cost(cli_fit, problem):
    assert sorted(problem.names) == sorted(cli_fit["parameters"].keys())
    theta = np.array([cli_fit["parameters"][n] for n in problem.names])
    e = problem.evaluate(theta)
    assert e["ok"] == (cli_fit["status"] == "ok")  # the GA's few evaluations may miss levels
    assert e["cost_j"] == cli_fit["cost_j"]
    assert e["mean_deviation_pct"] == cli_fit["mean_deviation_pct"]
    assert len(e["residuals"]) == problem.level_count == len(problem.sigma_j)


def test_progress_reports_the_search_and_false_cancels_with_best_so_far(problem):
    seen = []

    def progress(info):
        seen.append(info)
        return len(seen) < 3

    result = problem.fit(method="cmaes", evaluations=100000, threads=1, progress=progress)
    assert result["status"] == "cancelled"
    assert result["evaluations"] < 100000
    assert {"fraction", "stage", "evaluations", "best_weighted_cost", "best_theta"} <= set(seen[0])
    assert len(seen[0]["best_theta"]) == len(problem.names)
    # θ in one order everywhere: names, the progress's best_parameters, the result's dicts.
    for info in seen:
        assert list(info["best_parameters"]) == problem.names
        assert list(info["best_parameters"].values()) == info["best_theta"]
    assert list(result["parameters"]) == problem.names
    for key in ("standard_errors", "intervals_95"):  # not in a cancelled fit's result
        assert key not in result or list(result[key]) == problem.names, key


@contextlib.contextmanager
def ctrl_c_once_the_fit_reports():
    """Yields the list a fit's progress callback is to fill (progress=reports.append); a Python
    thread presses Ctrl-C (SIGINT) once the list holds a report, i.e. while the fit runs. An
    alarm fails the test after a minute instead of letting it hang when that never happens."""
    reports = []
    fit_returned = threading.Event()

    def ctrl_c_once_running():
        while not reports and not fit_returned.is_set():
            time.sleep(0.001)
        if reports and not fit_returned.is_set():
            os.kill(os.getpid(), signal.SIGINT)

    def hang_guard(signum, frame):
        raise TimeoutError("no Ctrl-C stopped the fit within 60 s: the helper thread never ran "
                           "while the fit did, or the fit ignored the interrupt")

    # Ctrl-C raises KeyboardInterrupt, Python's default, even when started with SIGINT ignored
    # (as a shell's background job is).
    previous_int = signal.signal(signal.SIGINT, signal.default_int_handler)
    previous = signal.signal(signal.SIGALRM, hang_guard)
    signal.setitimer(signal.ITIMER_REAL, 60)
    helper = threading.Thread(target=ctrl_c_once_running)
    helper.start()
    try:
        yield reports
    finally:
        # Read from the kernel, not from Python: once the alarm has fired, nothing is left.
        guard_left_s = signal.getitimer(signal.ITIMER_REAL)[0]
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        fit_returned.set()
        helper.join()
        signal.signal(signal.SIGINT, previous_int)
    # The alarm's handler runs Python code, during which the helper could run too: a Ctrl-C
    # that came only then proves nothing.
    assert guard_left_s > 0, "the fit was interrupted only after the hang guard fired"


def test_ctrl_c_during_a_fit_raises_keyboard_interrupt_and_stops_it(problem):
    # A million evaluations would take the better part of an hour: returning at all is the fit
    # giving up on Ctrl-C (how fast is a figure for a benchmark, not a test).
    with ctrl_c_once_the_fit_reports() as reports:
        with pytest.raises(KeyboardInterrupt):
            problem.fit(method="cmaes", evaluations=1000000, threads=0, progress=reports.append)
    assert reports, "the fit was interrupted while it ran, after its first report"
    # The interrupted fit let go of its workers: the next one runs to its end.
    result = problem.fit(method="cmaes", evaluations=60, threads=0)
    assert result["status"] != "cancelled"


def test_gil_is_released_while_a_fit_runs(problem):
    # While the fit runs, the calling thread runs no Python code: its progress callback is the C
    # builtin list.append, which never hands the GIL over. So the helper thread can see a report
    # and press Ctrl-C while the fit runs only if the fit let go of the GIL; a fit that held it
    # would run its million evaluations to the end (the hang guard fails it long before).
    with ctrl_c_once_the_fit_reports() as reports:
        with pytest.raises(KeyboardInterrupt):
            problem.fit(method="cmaes", evaluations=1000000, threads=1, progress=reports.append)


def test_fit_errors_raise_value_error_with_the_cli_message(tmp_path):
    random = str(SAMPLES / "random.flac")
    message = cli_error("fit", random, "--out", tmp_path / "f.json")
    with pytest.raises(ValueError) as error:
        oscilab.fit(random)
    assert str(error.value) == message
    with pytest.raises(ValueError, match="unknown"):
        oscilab.fit(STEPPED, method="newton")
    with pytest.raises(ValueError, match="population: must be at least 2"):
        oscilab.fit(STEPPED, population=1)


# Small budgets, H = 3 and a fixed error floor: the same code as the defaults. Still about a minute
# a diagnosis on 2 cores (the hysteresis candidates' harmonic balance), so each of the CLI and
# Python runs once, side by side, and the tests below share them.
DIAGNOSE = {"baseline_evaluations": 20, "candidate_evaluations": 10, "max_steps": 1,
            "threads": 1, "max_seconds": 0, "model_error": 0.05, "harmonics": 3,
            "max_harmonics": 3}


@pytest.fixture(scope="module")
def diagnoses(tmp_path_factory, py_analysis):
    """The CLI's report.json and Python's report with its progress reports, of one diagnosis."""
    out = tmp_path_factory.mktemp("diagnose")
    options = [f"--{key.replace('_', '-')}" for key in DIAGNOSE]
    args = [str(a) for pair in zip(options, DIAGNOSE.values()) for a in pair]
    cli = subprocess.Popen([cli_path(), "diagnose", *STEPPED, "--out", str(out), "--no-png",
                            *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        reports = []
        report = oscilab.diagnose(py_analysis, **DIAGNOSE, progress=reports.append)
    finally:
        _, stderr = cli.communicate()
    assert cli.returncode == 0, stderr
    return read_json(out / "report.json"), report, reports


def test_diagnose_report_equals_cli_report(diagnoses):
    cli, report, _ = diagnoses
    report = dict(report)
    report["records"] = cli["records"]  # the CLI lists paths as given, an Analysis its names
    report.pop("final_model_object", None)
    assert without_timing(report) == without_timing(cli)
    assert report["verdict"] == cli["verdict"]
    assert report["baseline"]["cost_j"] == cli["baseline"]["cost_j"]


def test_diagnose_progress_says_its_phases_in_order(diagnoses):
    _, _, reports = diagnoses
    phases = [r["phase"] for r in reports]
    assert phases[0] == "baseline" and phases[-1] == "done"
    # One step at most (max_steps=1): the phases never go back.
    order = ["baseline", "settling", "candidates", "finalists", "accepting", "done"]
    indices = [order.index(p) for p in phases]
    assert indices == sorted(indices)
    fractions = [r["fraction"] for r in reports]
    assert fractions == sorted(fractions) and fractions[-1] == 1.0
    assert all(isinstance(r["message"], str) and r["message"] for r in reports)
    assert reports[-1]["max_steps"] == 1
    baseline = [r for r in reports if r["phase"] == "baseline"]
    assert baseline[-1]["evaluations"] > 0
    assert "of 20 evaluations" in baseline[-1]["message"]


def test_merge_equals_cli_merge(tmp_path, cli_fit):
    # Two FIT JSONs: the CLI's fit, and the same with one parameter and its error left out (the
    # table then holds NaN there, the CSV an empty field).
    a, b = tmp_path / "a.json", tmp_path / "b,quoted.json"
    a.write_text(json.dumps(cli_fit))
    other = json.loads(json.dumps(cli_fit))
    dropped = next(iter(other["parameters"]))
    del other["parameters"][dropped]
    other.get("standard_errors", {}).pop(dropped, None)
    b.write_text(json.dumps(other))
    run_cli("merge", a, b, "--out", tmp_path / "m.csv")
    with open(tmp_path / "m.csv", newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    table = oscilab.merge([a, os.fsencode(b)])
    assert list(table) == header
    for c, name in enumerate(header):
        column = table[name]
        assert column.shape == (2,)
        for k in range(2):
            cell = body[k][c]
            if column.dtype.kind == "U":
                assert column[k] == (cell if name != "fit" else str([a, b][k]))
            elif column.dtype == np.int64:
                assert column[k] == int(cell)
            else:
                assert column.dtype == np.float64
                # The CSV keeps 9 significant digits.
                assert (np.isnan(column[k]) and cell == "") or \
                    column[k] == pytest.approx(float(cell), rel=1e-8)
    assert np.isnan(table[dropped][1]) and not np.isnan(table[dropped][0])


def test_merge_errors_name_the_argument_and_the_file(tmp_path):
    with pytest.raises(oscilab.InputError, match="fits"):
        oscilab.merge([])
    bad = tmp_path / "not_a_fit.json"
    bad.write_text('{"cost_j": 1}')
    message = cli_error("merge", bad, "--out", tmp_path / "m.csv")
    with pytest.raises(oscilab.InputError) as error:
        oscilab.merge(bad)
    assert str(error.value) == message
    with pytest.raises(oscilab.MissingFileError):
        oscilab.merge(tmp_path / "absent.json")
