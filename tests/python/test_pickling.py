"""Recording and Model as Python values: pickled (multiprocessing, joblib, Dask), compared with ==,
and a recording's samples as read-only views of its own memory instead of a copy per access."""

import concurrent.futures
import gc
import multiprocessing
import pickle

import numpy as np
import pytest

import oscilab
from conftest import STEPPED


def test_a_read_recording_pickles_to_an_equal_one_with_its_stored_values_and_origin():
    rec = oscilab.read_recording(STEPPED[0])
    copy = pickle.loads(pickle.dumps(rec))
    assert copy == rec
    assert copy.sidecar == rec.sidecar
    np.testing.assert_array_equal(copy.samples, rec.samples)
    np.testing.assert_array_equal(copy.samples_stored, rec.samples_stored)
    assert (copy.source_path, copy.container) == (rec.source_path, rec.container)
    assert copy.describe() == rec.describe()


def test_a_recording_made_in_memory_pickles_with_its_invalid_nan_samples():
    rec = oscilab.read_recording(STEPPED[0])
    sidecar = rec.sidecar
    sidecar["invalid_intervals"] = [{"start_s": 0.0, "end_s": 0.01}]
    samples = np.array(rec.samples)
    samples[2, :] = np.nan
    made = oscilab.Recording(sidecar, samples)
    copy = pickle.loads(pickle.dumps(made))
    assert copy == made  # NaN equals NaN here: the same recording
    assert copy.samples_stored is None
    assert made != rec


def test_recordings_are_equal_by_sidecar_and_samples_not_by_origin():
    rec = oscilab.read_recording(STEPPED[0])
    assert rec == oscilab.read_recording(STEPPED[0])
    assert oscilab.Recording(rec.sidecar, rec.samples) == rec
    assert rec != oscilab.read_recording(STEPPED[1])
    samples = np.array(rec.samples)
    samples[-1, 1] += 1e-9
    assert oscilab.Recording(rec.sidecar, samples) != rec
    assert rec != "recording"
    with pytest.raises(TypeError):
        hash(rec)


def channel_count(recording):
    return recording.samples.shape[1], float(recording.samples.sum())


def test_a_recording_goes_to_another_process():
    rec = oscilab.read_recording(STEPPED[0])
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=context) as pool:
        assert pool.submit(channel_count, rec).result(timeout=60) == channel_count(rec)


def test_models_are_equal_by_their_json_and_pickle():
    assert oscilab.Model.paper() == oscilab.Model.paper()
    assert oscilab.Model.paper() != oscilab.Model.illustrative()
    assert oscilab.Model.paper(ks=1.2) != oscilab.Model.paper()
    fitted = oscilab.Model.paper(ks=1.2)
    assert oscilab.Model.from_json(fitted.to_json()) == fitted
    for model in (oscilab.Model.paper(), oscilab.Model.illustrative(), oscilab.Model.paper(ks=1.2)):
        copy = pickle.loads(pickle.dumps(model))
        assert copy == model
        assert copy.to_json() == model.to_json()
    assert oscilab.Model.paper() != 1
    with pytest.raises(TypeError):
        hash(oscilab.Model.paper())


def test_samples_are_read_only_views_of_the_recording():
    rec = oscilab.read_recording(STEPPED[0])
    samples = rec.samples
    assert not samples.flags.writeable
    assert np.shares_memory(samples, rec.samples)  # no copy per access
    with pytest.raises(ValueError, match="read-only"):
        samples[0, 0] = 1.0
    for i, name in enumerate(rec.channel_names):
        assert np.shares_memory(rec[name], samples)
        assert not rec.channel(name).flags.writeable
        np.testing.assert_array_equal(rec[name], samples[:, i])
    writable = np.array(samples)
    writable[0, 0] = 1.0
    assert not np.shares_memory(writable, samples)
    expected = samples.copy()
    del rec
    gc.collect()
    np.testing.assert_array_equal(samples, expected)  # the view keeps the recording alive
