"""Typing: the stubs (oscilab/__init__.pyi) list exactly the module's public names and are what
python/generate_stubs.py makes of the built module; py.typed is there; inspect.signature works on
every compiled function, constructor and method, with the names and defaults of the bindings."""

import ast
import importlib.util
import inspect
import types
from pathlib import Path

import pytest

import oscilab
from conftest import SOURCE_DIR

PACKAGE = Path(oscilab.__file__).resolve().parent
SOURCE_STUBS = SOURCE_DIR / "python" / "oscilab" / "__init__.pyi"


def stub_tree():
    return ast.parse(SOURCE_STUBS.read_text())


def stub_public_names(tree):
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets)
    return {n for n in names if not n.startswith("_")}


def module_public_names():
    return {name for name, value in vars(oscilab).items()
            if not name.startswith("_") and not isinstance(value, types.ModuleType)}


def test_the_module_exports_what_all_lists():
    assert module_public_names() == set(oscilab.__all__)


def test_the_stubs_list_exactly_the_modules_public_names():
    tree = stub_tree()
    assert stub_public_names(tree) == set(oscilab.__all__)
    all_assignment = next(node for node in tree.body if isinstance(node, ast.Assign)
                          and any(t.id == "__all__" for t in node.targets))
    assert ast.literal_eval(all_assignment.value) == oscilab.__all__
    assert any(isinstance(node, ast.AnnAssign) and node.target.id == "__version__"
               for node in tree.body)


def test_the_stubs_are_what_the_generator_makes_of_the_module():
    spec = importlib.util.spec_from_file_location(
        "generate_stubs", SOURCE_DIR / "python" / "generate_stubs.py")
    generator = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(generator)
    assert generator.stubs_text() == SOURCE_STUBS.read_text(), (
        "the stubs differ from the module: run python/generate_stubs.py")


def test_the_package_is_typed_where_it_is_imported_from():
    assert (PACKAGE / "py.typed").is_file()
    assert (PACKAGE / "__init__.pyi").read_text() == SOURCE_STUBS.read_text()


def callables():
    """(qualified name, callable) of every public function, constructor and method."""
    for name in oscilab.__all__:
        obj = getattr(oscilab, name)
        if not inspect.isclass(obj):
            yield name, obj
        elif not issubclass(obj, BaseException):
            if "__init__" in vars(obj) and type(vars(obj)["__init__"]).__name__ == "instancemethod":
                yield name, obj
            for member_name, member in vars(obj).items():
                if not member_name.startswith("_") and not isinstance(member, property):
                    yield f"{name}.{member_name}", getattr(obj, member_name)


@pytest.mark.parametrize("name, function", list(callables()), ids=lambda v: str(v))
def test_inspect_signature_works_and_matches_the_stubs(name, function):
    signature = inspect.signature(function)
    stub = stub_function(name)
    stub_names = [a.arg for a in stub.args.posonlyargs + stub.args.args + stub.args.kwonlyargs]
    if stub_names[:1] == ["self"] and "." not in name:  # a constructor: the class's signature
        stub_names = stub_names[1:]
    names = [p.name for p in signature.parameters.values()
             if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    assert names == stub_names
    keyword_only = [p.name for p in signature.parameters.values() if p.kind is p.KEYWORD_ONLY]
    assert keyword_only == [a.arg for a in stub.args.kwonlyargs]


def stub_function(name):
    tree = stub_tree()
    owner, _, member = name.rpartition(".")
    if not owner and inspect.isclass(getattr(oscilab, name)):
        owner, member = name, "__init__"
    body = tree.body
    if owner:
        body = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == owner).body
    return next(n for n in body if isinstance(n, ast.FunctionDef) and n.name == member)


def test_signatures_carry_defaults_and_types():
    signature = inspect.signature(oscilab.fit)
    assert signature.parameters["method"].default == "cmaes"
    assert signature.parameters["method"].kind is inspect.Parameter.KEYWORD_ONLY
    assert signature.parameters["freq_hz"].default is None
    assert signature.parameters["freq_hz"].annotation == "float | None"
    assert inspect.signature(oscilab.hbm_branch).parameters["f0_n"].default == (0.1, 3.7)
    assert list(inspect.signature(oscilab.Recording).parameters) == ["sidecar", "samples"]
    assert list(inspect.signature(oscilab.Model.paper().well).parameters) == ["well"]


def test_wrapped_functions_still_document_themselves_and_pickle_by_name():
    import pickle

    assert "KeyboardInterrupt" in oscilab.fit.__doc__
    assert oscilab.fit.__module__ == "oscilab"
    assert pickle.loads(pickle.dumps(oscilab.fit)) is oscilab.fit
    assert pickle.loads(pickle.dumps(oscilab.Model.well)) is oscilab.Model.well
