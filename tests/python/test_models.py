"""Models: the paper's and the illustrative, JSON both ways, built from terms; equilibria and
eq. (4) frequencies equal oscilab-cli model's."""

import json
import pickle
import struct

import numpy as np
import pytest

import oscilab
from conftest import cli_error, read_json, run_cli


@pytest.mark.parametrize("name", ["paper", "illustrative"])
def test_model_json_and_summary_equal_cli_output(tmp_path, name):
    run_cli("model", name, "--out", tmp_path / "m.json", "--summary", tmp_path / "s.json")
    model = getattr(oscilab.Model, name)()
    assert model.to_json() == read_json(tmp_path / "m.json")
    assert model.summary() == read_json(tmp_path / "s.json")
    assert oscilab.Model.from_spec(name).to_json() == model.to_json()


def test_equilibria_follow_the_contract_and_eq4():
    model = oscilab.Model.paper()
    eq = model.equilibria()
    assert [e["stable"] for e in eq] == [True, False, True]
    assert eq[0]["z_m"] < eq[1]["z_m"] < eq[2]["z_m"]
    assert eq[1]["linear_frequency_hz"] is None
    for e in (eq[0], eq[2]):  # eq. (4): f = √(U''(z*)/m) / 2π
        assert e["linear_frequency_hz"] == pytest.approx(
            np.sqrt(e["stiffness_n_m"] / model.mass_kg) / (2 * np.pi), rel=1e-12)
    summary = model.summary()["equilibria"]
    assert [e["z_m"] for e in summary] == [e["z_m"] for e in eq]
    assert model.well("negative")["z_m"] == eq[0]["z_m"]


def test_model_round_trips_through_json_text_dict_and_file(tmp_path):
    model = oscilab.Model.paper(c_ns_m=3.0, ks=1.2)
    assert model.to_json() != oscilab.Model.paper().to_json()
    again = oscilab.Model.from_json(json.dumps(model.to_json()))
    assert again.to_json() == model.to_json()
    model.save(tmp_path / "m.json")
    assert oscilab.Model.load(tmp_path / "m.json").to_json() == model.to_json()
    run_cli("model", tmp_path / "m.json", "--summary", tmp_path / "s.json")
    assert model.summary() == read_json(tmp_path / "s.json")


def test_model_built_from_terms_equals_the_same_json():
    paper = oscilab.Model.paper()
    built = oscilab.Model(paper.mass_kg, paper.terms, paper.name)
    assert built.to_json() == paper.to_json()
    linear = oscilab.Model(1.0, [{"type": "polynomial-stiffness", **_linear_stiffness(paper)}])
    assert linear.mass_kg == 1.0


def _linear_stiffness(paper):
    stiffness = next(t for t in paper.terms if t["type"] == "polynomial-stiffness")
    return {k: v for k, v in stiffness.items() if k != "type"}


def test_restoring_force_is_elementwise_and_elastic_part_vanishes_at_equilibria():
    model = oscilab.Model.paper()
    z = np.array([e["z_m"] for e in model.equilibria()])
    np.testing.assert_allclose(model.elastic_force(z), 0.0, atol=1e-9)
    r = model.restoring_force(z, 0.0)
    assert r.shape == (3,)
    assert isinstance(model.restoring_force(0.01, 0.1), float)
    assert model.potential_j(z[0]) != model.potential_j(z[2])


def test_bad_model_file_raises_the_cli_message(tmp_path):
    data = oscilab.Model.paper().to_json()
    data["terms"][0]["type"] = "no-such-term"
    (tmp_path / "bad.json").write_text(json.dumps(data))
    message = cli_error("model", tmp_path / "bad.json")
    with pytest.raises(ValueError) as error:
        oscilab.Model.load(tmp_path / "bad.json")
    assert str(error.value) == message
    with pytest.raises(ValueError, match="terms\\[0\\]"):
        oscilab.Model(1.0, [{"type": "no-such-term"}])
    with pytest.raises(ValueError):
        oscilab.Model(-1.0, paper_terms())


def paper_terms():
    return oscilab.Model.paper().terms


def test_missing_model_file_raises_os_error(tmp_path):
    with pytest.raises(OSError):
        oscilab.Model.load(tmp_path / "missing.json")


def test_json_nested_too_deep_raises_value_error_not_a_crash():
    # 100 000 nested arrays would overflow the stack when copied; a list holding itself never ends.
    deep = '{"mass_kg": 0.26, "terms": [], "x": ' + "[" * 100000 + "]" * 100000 + "}"
    with pytest.raises(ValueError, match="^model: JSON nested deeper than 64 levels"):
        oscilab.Model.from_json(deep)
    itself = []
    itself.append(itself)
    with pytest.raises(ValueError, match="nested deeper than 64 levels"):
        oscilab.Model.from_json({"mass_kg": 0.26, "terms": [], "x": itself})


def test_a_pickled_model_state_nested_too_deep_is_refused_not_a_crash():
    data = pickle.dumps(oscilab.Model.paper(), 2)
    # The state is the model JSON, a BINUNICODE item: 'X', its length (u32 LE), the text.
    at = data.index(b"X")
    while data[at + 5:at + 6] != b"{":
        at = data.index(b"X", at + 1)
    length = struct.unpack("<I", data[at + 1:at + 5])[0]
    deep = b'{"x": ' + b"[" * 100000 + b"]" * 100000 + b"}"
    bomb = data[:at] + b"X" + struct.pack("<I", len(deep)) + deep + data[at + 5 + length:]
    with pytest.raises(ValueError, match="^Model state: JSON nested deeper than 64 levels"):
        pickle.loads(bomb)
