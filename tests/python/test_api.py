"""The module's surface: every public function, class, method and property documents itself,
and the package imports without pandas or matplotlib."""

import inspect

import oscilab


def public_members(cls):
    """The class's own public members: not those an exception inherits from Python's (args ...)."""
    inherited = {name for base in cls.__mro__ if base.__module__ == "builtins"
                 for name in vars(base)}
    for name, member in inspect.getmembers(cls):
        if not name.startswith("_") and name not in inherited:
            yield name, member


def described(obj, name):
    """A docstring beyond the signature line pybind11 writes for every function."""
    doc = (getattr(obj, "__doc__", None) or "").strip()
    if doc.startswith(name + "("):
        doc = doc.split("\n", 1)[1].strip() if "\n" in doc else ""
    return bool(doc)


def test_every_public_function_and_class_has_a_docstring():
    for name in oscilab.__all__:
        obj = getattr(oscilab, name)
        assert described(obj, name), name
        if inspect.isclass(obj):
            for member_name, member in public_members(obj):
                assert described(member, member_name), f"{name}.{member_name}"


def test_keyword_arguments_and_units_are_documented():
    doc = oscilab.analyze.__doc__
    assert "freq_hz" in doc and "[Hz]" in doc
    assert "f0_n" in oscilab.hbm_branch.__doc__ and "[N]" in oscilab.hbm_branch.__doc__
    assert "KeyboardInterrupt" in oscilab.fit.__doc__


def test_generators_of_paths_are_read_once():
    from conftest import STEPPED
    problem = oscilab.prepare_fit((p for p in STEPPED), model_error=0.05)
    assert problem.records == STEPPED


def test_a_forked_child_runs_jobs_of_its_own():
    import multiprocessing
    from conftest import STEPPED
    oscilab.analyze(STEPPED[0])  # the parent's worker thread exists now
    context = multiprocessing.get_context("fork")
    with context.Pool(1) as pool:
        levels = pool.apply_async(_levels_of, (STEPPED[0],)).get(timeout=60)
    assert levels == len(oscilab.analyze(STEPPED[0]).edc["f0_n"])


def _levels_of(path):
    return len(oscilab.analyze(path).edc["f0_n"])
