"""fit(), prepare_fit() and diagnose(): the CLI's FIT JSON and report.json from the same code,
progress and cancellation, Ctrl-C (KeyboardInterrupt once the fit stopped) and the GIL released
while C++ works."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import oscilab
from conftest import SAMPLES, STEPPED, cli_error, read_json, run_cli

GA = {"method": "ga", "population": 8, "generations": 2, "seed": 3, "threads": 1}
# A fixed 5 % model-error floor instead of the σ budget's calibration (harmonic balance up to
# H = 63), which would take most of the suite's time; the budget is the same code either way.
COST = {"model_error": 0.05}
# Keys that hold wall-clock time, which two runs never share.
TIMING_KEYS = {"seconds"}


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


def test_ctrl_c_during_a_fit_raises_keyboard_interrupt_and_stops_it(problem):
    def interrupt():
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(0.5, interrupt)
    timer.start()
    # A million evaluations would take the better part of an hour: returning at all is the fit
    # giving up on Ctrl-C (how fast is a figure for a benchmark, not a test).
    with pytest.raises(KeyboardInterrupt):
        problem.fit(method="cmaes", evaluations=1000000, threads=0)
    timer.join()
    # The interrupted fit let go of its workers: the next one runs to its end.
    result = problem.fit(method="cmaes", evaluations=60, threads=0)
    assert result["status"] != "cancelled"


def test_gil_is_released_while_a_fit_runs(problem):
    counter = {"n": 0, "run": True}

    def count():
        while counter["run"]:
            counter["n"] += 1

    thread = threading.Thread(target=count)
    thread.start()
    time.sleep(0.05)
    before = counter["n"]
    start = time.monotonic()
    problem.fit(method="cmaes", evaluations=60, threads=1)
    elapsed = time.monotonic() - start
    during = counter["n"] - before
    counter["run"] = False
    thread.join()
    assert elapsed > 0.05
    # A pure-Python loop counts millions per second; holding the GIL would leave it near zero.
    assert during > 10000 * elapsed, (during, elapsed)


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


# Small budgets, H = 3 and a fixed error floor: seconds, and the same code as the defaults.
DIAGNOSE = ["--baseline-evaluations", 20, "--candidate-evaluations", 10, "--max-steps", 1,
            "--threads", 1, "--max-seconds", 0, "--no-png", "--model-error", 0.05,
            "--harmonics", 3, "--max-harmonics", 3]


def test_diagnose_report_equals_cli_report(tmp_path, py_analysis):
    run_cli("diagnose", *STEPPED, "--out", tmp_path, *DIAGNOSE)
    cli = read_json(tmp_path / "report.json")
    report = oscilab.diagnose(py_analysis, baseline_evaluations=20, candidate_evaluations=10,
                              max_steps=1, threads=1, max_seconds=0, model_error=0.05,
                              harmonics=3, max_harmonics=3)
    report["records"] = cli["records"]  # the CLI lists paths as given, an Analysis its names
    report.pop("final_model_object", None)
    assert without_timing(report) == without_timing(cli)
    assert report["verdict"] == cli["verdict"]
    assert report["baseline"]["cost_j"] == cli["baseline"]["cost_j"]
