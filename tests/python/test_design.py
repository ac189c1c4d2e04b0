"""adaptive_test(): the same loop as `oscilab-cli adaptive-test` (decision for decision on the same
settings), its progress with each decision, a cancel, and its refused arguments."""

import json
import math

import pytest

import oscilab
from conftest import run_cli

# A small test, seconds long: a two-level pilot in each well, one candidate against the baseline,
# short fits, at most two adaptive levels, a final diagnosis bounded to a few seconds.
SMALL = dict(pilot_levels_n=[0.5, 1.5], hold_s=6.0, effects=["quadratic-damping"],
             global_evaluations=0, initial_evaluations=40, refit_evaluations=20, max_levels=2,
             threads=2, max_seconds=3.0)
SMALL_CLI = ["--pilot", "0.5,1.5", "--hold", "6",
             "--effects", "quadratic-damping", "--global-evaluations", "0",
             "--initial-evaluations", "40", "--refit-evaluations", "20", "--max-levels", "2",
             "--threads", "2", "--max-seconds", "3"]
TIMINGS = ("time_s", "proposal_s", "refit_s")


@pytest.fixture(scope="module")
def rig_model(tmp_path_factory):
    """The paper's model with quadratic damping (c2 = 6 N s²/m²) hidden in it, as a JSON file."""
    model = oscilab.Model.paper().to_json()
    model["terms"].append({"type": "quadratic-damping", "c2_ns2_m2": 6.0})
    path = tmp_path_factory.mktemp("rig") / "quad.json"
    path.write_text(json.dumps(model))
    return path


def without_timings(decisions):
    """The decisions without their wall-clock times, as the CLI's JSON text writes them: a NaN
    (a reduced χ² with fewer levels than parameters) is a float in Python and null in JSON."""
    def as_written(value):
        if isinstance(value, dict):
            return {k: as_written(v) for k, v in value.items()}
        if isinstance(value, list):
            return [as_written(v) for v in value]
        return None if isinstance(value, float) and math.isnan(value) else value

    return [as_written({k: v for k, v in d.items() if k not in TIMINGS}) for d in decisions]


def test_adaptive_test_makes_the_clis_decisions(rig_model, tmp_path):
    seen = {}

    def progress(info):
        if "decision" in info:
            seen[info["decision"]["decision"]] = info["decision"]
        assert 0.0 <= info["fraction"] <= 1.0

    result = oscilab.adaptive_test(rig_model, tmp_path / "py", progress=progress, **SMALL)
    assert isinstance(result, oscilab.Result)
    run_cli("adaptive-test", "--source", "rig", "--rig-model", rig_model, "--out", tmp_path / "cli",
            *SMALL_CLI)
    cli_decisions = [json.loads(line) for line in open(tmp_path / "cli" / "decisions.jsonl")]
    cli_report = json.loads((tmp_path / "cli" / "report.json").read_text())

    assert without_timings(result["decisions"]) == without_timings(cli_decisions)
    assert result["decisions"][-1]["stop"] and not any(d["stop"] for d in result["decisions"][:-1])
    loop = result["adaptive_test"]
    assert loop["levels"] == cli_report["adaptive_test"]["levels"] == 4 + loop["adaptive_levels"]
    assert loop["leader"] == cli_report["adaptive_test"]["leader"]
    assert result["shaker_time_s"] == cli_report["shaker_time_s"]
    # The pilot and each adaptive level: a recording with its sidecar, named as the CLI names it.
    assert [p.rsplit("/", 1)[1] for p in result["recordings"]] == \
        [p.rsplit("/", 1)[1] for p in cli_report["records"]]
    assert all((tmp_path / "py" / p.rsplit("/", 1)[1]).exists() for p in result["recordings"])
    assert "verdict" in result and result["status"] in ("ok", "incomplete")
    # Progress carried each decision it saw as the result lists it (at least the last: reports
    # coalesce, and the last report of a job is always delivered).
    assert seen and max(seen) == len(result["decisions"]) - 1
    assert without_timings(list(seen.values())) == \
        without_timings([result["decisions"][i] for i in seen])


def test_adaptive_test_cancels_from_its_progress_callback(rig_model, tmp_path):
    result = oscilab.adaptive_test(rig_model, tmp_path, progress=lambda info: "decision" not in info,
                                   **SMALL)
    assert result["status"] == "cancelled"
    assert "verdict" not in result  # no final diagnosis
    assert len(result["decisions"]) >= 1
    assert len(result["recordings"]) >= 1


@pytest.mark.parametrize("arguments, words", [
    (dict(wells="left"), 'wells: "left"'),
    (dict(effects=["quadratic-damping", "drag"]), 'unknown effect "drag"'),
    (dict(f0_range_n=[1.0]), "f0_range_n"),
    (dict(leader_weight=2.0), "^leader_weight: must be between 0.5 and 1"),
    (dict(pilot_levels_n=[]), "pilot_levels_n"),
    (dict(budget_s=-5.0), "^budget_s: must be a positive"),
    (dict(freq_step_hz=0.0), "^freq_step_hz: must be a positive"),
    (dict(lead_in_s=-1.0), "lead_in_s"),
])
def test_adaptive_test_refuses_bad_arguments_before_any_run(rig_model, tmp_path, arguments, words):
    with pytest.raises(oscilab.InputError, match=words.replace("(", r"\(")):
        oscilab.adaptive_test(rig_model, tmp_path / "out", **{**SMALL, **arguments})
    assert not (tmp_path / "out").exists()
