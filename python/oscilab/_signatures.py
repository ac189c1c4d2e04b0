"""Signatures of the compiled functions, read from the first line of the docstring pybind11 writes
(``fit(recordings: object, *, method: str = 'cmaes', ...) -> dict``), with the C++ side's loose
types (``object``) replaced by what each argument takes. One source for both
``inspect.signature`` at run time (``oscilab/__init__.py``) and the stubs
(``python/generate_stubs.py`` → ``oscilab/__init__.pyi``), so neither can drift from the bindings.
"""

import ast
import inspect
import re

# The stubs' type aliases (private names, defined at the top of __init__.pyi).
ALIASES = {
    "_StrPath": "str | bytes | os.PathLike[str] | os.PathLike[bytes]",
    "_Recordings": "_StrPath | Recording | Analysis | Iterable[_StrPath | Recording]",
    "_ModelLike": "Model | dict[str, Any] | _StrPath",
    "_Progress": "Callable[[dict[str, Any]], object]",
}

# What an argument the bindings take as `object` accepts, by its keyword name (`| None` is added
# where its default is None).
ARGUMENT_TYPES = {
    "recordings": "_Recordings",
    "model": "_ModelLike",
    "progress": "_Progress",
    "path": "_StrPath",
    "fits": "_StrPath | Iterable[_StrPath]",
    "spec": "_StrPath",
    "record_to": "_StrPath",
    "sidecar": "dict[str, Any] | str",
    "samples": "ArrayLike | Mapping[str, ArrayLike]",
    "json": "dict[str, Any] | str",
    "theta": "ArrayLike",
    "z_m": "ArrayLike",
    "z_dot_m_s": "ArrayLike",
    "levels_n": "str | ArrayLike",
    "freq_hz": "float",
    "duration_s": "float",
    "excitation_freq_hz": "float",
    "z0_m": "float",
    "well": "str",
    "source": "str | os.PathLike[str] | Recording",
    "expected_sidecar": "dict[str, Any] | _StrPath",
    "calibration": "dict[str, Any] | _StrPath",
    "fd_zminus_n": "float",
    "fd_zero_n": "float",
    "fd_zplus_n": "float",
    "ks": "float",
    "c_ns_m": "float",
    "vt_m_s": "float",
    "rig_model": "_ModelLike",
    "out": "_StrPath",
    "f0_range_n": "tuple[float, float] | ArrayLike",
    "pilot_levels_n": "ArrayLike",
}

_NATIVE = "oscilab._native._oscilab."


def python_type(text):
    """A pybind11 type name as the stubs write it."""
    text = text.replace(_NATIVE, "")
    text = re.sub(r"numpy\.ndarray\[([^\]]*)\]", r"NDArray[\1]", text)
    for typing_name, builtin in (("List", "list"), ("Dict", "dict"), ("Tuple", "tuple")):
        text = re.sub(r"\b%s\[" % typing_name, builtin + "[", text)
    return "Any" if text == "object" else text


class _Default:
    """A default that is not a Python literal, shown as pybind11 wrote it."""

    def __init__(self, text):
        self.text = text

    def __repr__(self):
        return self.text


def parse(doc, name):
    """(parameters, return type) from a pybind11 docstring: parameters are (kind, name,
    annotation text, default text or None); None when the first line is not `name(...) -> T`
    (overloads, plain Python functions)."""
    first = (doc or "").lstrip().split("\n", 1)[0]
    if not first.startswith(name + "("):
        return None
    try:
        tree = ast.parse("def _f" + first[len(name):] + ": pass")
    except SyntaxError:
        return None
    function = tree.body[0]
    arguments = function.args
    parameters = []

    def add(kind, argument, default):
        annotation = ast.unparse(argument.annotation) if argument.annotation else None
        parameters.append((kind, argument.arg, annotation,
                           None if default is None else ast.unparse(default)))

    positional = arguments.posonlyargs + arguments.args
    defaults = [None] * (len(positional) - len(arguments.defaults)) + list(arguments.defaults)
    for i, argument in enumerate(positional):
        kind = "positional_only" if i < len(arguments.posonlyargs) else "positional_or_keyword"
        add(kind, argument, defaults[i])
    if arguments.vararg:
        add("var_positional", arguments.vararg, None)
    for argument, default in zip(arguments.kwonlyargs, arguments.kw_defaults):
        add("keyword_only", argument, default)
    if arguments.kwarg:
        add("var_keyword", arguments.kwarg, None)
    returns = ast.unparse(function.returns) if function.returns else "None"
    return parameters, returns


def argument_type(name, annotation, default):
    """The type an argument is written with: by name where the binding says `object`."""
    text = python_type(annotation) if annotation else "Any"
    if text == "Any" and name in ARGUMENT_TYPES:
        text = ARGUMENT_TYPES[name]
    if default == "None" and "None" not in text.split(" | ") and text != "Any":
        text += " | None"
    return text


def signature(doc, name, drop_first=False):
    """An inspect.Signature (annotations as text) from a pybind11 docstring, or None."""
    parsed = parse(doc, name)
    if parsed is None:
        return None
    parameters, returns = parsed
    if drop_first and parameters:
        parameters = parameters[1:]
    out = []
    for kind, arg, annotation, default in parameters:
        if default is None:
            value = inspect.Parameter.empty
        else:
            try:
                value = ast.literal_eval(default)
            except ValueError:
                value = _Default(default)
        out.append(inspect.Parameter(arg, getattr(inspect.Parameter, kind.upper()), default=value,
                                     annotation=argument_type(arg, annotation, default)))
    return inspect.Signature(out, return_annotation=python_type(returns))
