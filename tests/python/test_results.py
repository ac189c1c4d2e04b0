"""The reports of fit and diagnose: dicts with the CLI's keys (so equal to its JSON, written by
json.dump) that print short in a terminal and in Jupyter, and pickle as themselves."""

import inspect
import json
import pickle

import pytest

import oscilab
from conftest import STEPPED

SMALL = dict(harmonics=3, max_harmonics=3, model_error=0.01)


@pytest.fixture(scope="module")
def result():
    return oscilab.prepare_fit(STEPPED, **SMALL).fit(method="cmaes", evaluations=60, seed=1)


def test_a_fit_result_is_a_dict_that_prints_short(result):
    assert isinstance(result, oscilab.Result)
    assert isinstance(result, dict)
    full = json.dumps(result)
    text = repr(result)
    assert len(text) < 2000 < len(full)  # the levels and the history: sizes only
    assert text.startswith("oscilab.Result(")
    assert "status='ok'" in text
    assert f"levels=<list of {len(result['levels'])}>" in text
    for name, value in result["parameters"].items():  # small flat dicts in full
        assert f"'{name}': {value!r}" in text
    assert json.loads(full) == dict(result)


def test_jupyter_shows_the_same_as_a_table(result):
    html = result._repr_html_()
    assert html.startswith("<table>") and html.endswith("</table>")
    assert "status" in html and "&lt;list of" in html


def test_a_result_pickles_as_a_result(result):
    copy = pickle.loads(pickle.dumps(result))
    assert type(copy) is oscilab.Result
    assert copy == result


def test_fit_and_diagnose_say_they_return_a_result():
    assert inspect.signature(oscilab.fit).return_annotation == "Result"
    assert inspect.signature(oscilab.diagnose).return_annotation == "Result"
    assert inspect.signature(oscilab.FitProblem.fit).return_annotation == "Result"
