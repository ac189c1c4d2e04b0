"""Oscilab from Python: the same C++ core as ``oscilab-cli`` and the app.

Read and write recordings (any format the core reads), analyse them (EDC per stepped-sine level,
restoring-force surface), build models (the paper's, the illustrative, from JSON or from terms),
simulate them in time and with the virtual rig, follow harmonic-balance branches, fit the
friction model and diagnose missing effects, and run the live chain as an iterator.

Arrays are NumPy arrays in SI units (N, m, s, J, Hz, kg); tables are dicts of columns named like
the CLI's CSV columns, JSON results are dicts with the CLI's keys (docs/contracts.md). Errors are
oscilab.Error: bad input raises InputError (a ValueError) with the CLI's one-line message naming
the keyword argument, file, field or value; a file that cannot be opened or written raises
FileError (an OSError), MissingFileError (a FileNotFoundError) when it does not exist. Long
calls release the GIL, report progress to an optional callback and stop on Ctrl-C
(KeyboardInterrupt, raised once the C++ job has stopped). Functions and methods have real
signatures (inspect.signature) and the package ships type stubs. See docs/python.md.
"""

from ._native._oscilab import (  # noqa: F401  (re-exported)
    Analysis,
    Error,
    FileError,
    FitProblem,
    InputError,
    LiveSession,
    MissingFileError,
    Model,
    Recording,
    adaptive_test,
    amplitude_sweep,
    analyze,
    bifurcation_map,
    describe_recording,
    diagnose,
    draft_sidecar,
    fit,
    hbm_branch,
    live,
    merge,
    prepare_fit,
    read_recording,
    simulate,
    virtual_rig,
    write_recording,
)
from ._native._oscilab import __version__  # noqa: F401  (CMakeLists.txt's project VERSION)

__all__ = [
    "Analysis",
    "Error",
    "FileError",
    "FitProblem",
    "InputError",
    "LiveSession",
    "MissingFileError",
    "Model",
    "Recording",
    "Result",
    "adaptive_test",
    "amplitude_sweep",
    "analyze",
    "bifurcation_map",
    "describe_recording",
    "diagnose",
    "draft_sidecar",
    "fit",
    "hbm_branch",
    "live",
    "merge",
    "prepare_fit",
    "read_recording",
    "simulate",
    "to_dataframe",
    "virtual_rig",
    "write_recording",
]


class Result(dict):
    """A result with the CLI's JSON keys (fit, diagnose): a dict in every way, which prints short.

    ``repr()`` gives the status and the other numbers and words at the top level, and only the
    size of each list or dict (a fit's levels and history alone run to ~60 kB of text);
    Jupyter shows the same as a table (``_repr_html_``). ``dict(result)`` or ``result[key]``
    for the rest; ``json.dump(result, f)`` writes the CLI's file.
    """

    def _rows(self):
        for key, value in self.items():
            if isinstance(value, dict) and len(value) <= 8 and all(
                    isinstance(v, (int, float, str, bool)) or v is None for v in value.values()):
                yield key, value, True  # small and flat, such as parameters: in full
            elif isinstance(value, (dict, list)):
                kind = "dict" if isinstance(value, dict) else "list"
                yield key, f"<{kind} of {len(value)}>", False
            elif isinstance(value, str) and len(value) > 80:
                yield key, f"<str of {len(value)}>", False
            else:
                yield key, value, True

    def __repr__(self):
        parts = [f"{key}={value!r}" if plain else f"{key}={value}"
                 for key, value, plain in self._rows()]
        return "oscilab.Result(" + ", ".join(parts) + ")"

    def _repr_html_(self):
        import html

        rows = "".join(f"<tr><th style='text-align:left'>{html.escape(str(key))}</th>"
                       f"<td style='text-align:left'>{html.escape(repr(value) if plain else value)}"
                       "</td></tr>" for key, value, plain in self._rows())
        return f"<table><caption>oscilab.Result</caption>{rows}</table>"

    def __reduce__(self):
        return (Result, (dict(self),))


def to_dataframe(table):
    """A table (a dict of equal-length columns, e.g. ``Analysis.edc``) as a pandas.DataFrame.

    pandas is optional: raises ImportError naming it when it is not installed; the dict form
    works without it.
    """
    try:
        import pandas
    except ImportError as error:
        raise ImportError("to_dataframe needs pandas (python3-pandas); the dict form "
                          "(e.g. Analysis.edc) works without it") from error
    return pandas.DataFrame({name: list(column) if isinstance(column, list) else column
                             for name, column in table.items()})


def _edc_dataframe(self):
    """The EDC table (``self.edc``) as a pandas.DataFrame; ImportError without pandas."""
    return to_dataframe(self.edc)


Analysis.edc_dataframe = _edc_dataframe


def _give_signatures():
    """inspect.signature for the compiled functions, constructors and methods: each function and
    method becomes a thin Python wrapper whose __signature__ is the one pybind11 states in its
    docstring (oscilab/_signatures.py, which the stubs come from too); constructors give theirs
    as the class's __signature__. The reports of fit and diagnose come back as a Result."""
    import functools

    from . import _signatures

    # The calls whose dict is a report with the CLI's JSON keys: returned as a Result.
    reports = {"fit", "diagnose", "adaptive_test", "FitProblem.fit"}

    def wrap(native, signature, qualname):
        if qualname in reports:
            signature = signature.replace(return_annotation="Result")

            @functools.wraps(native)
            def wrapper(*args, **kwargs):
                return Result(native(*args, **kwargs))
        else:
            @functools.wraps(native)
            def wrapper(*args, **kwargs):
                return native(*args, **kwargs)

        wrapper.__signature__ = signature
        wrapper.__module__ = __name__
        wrapper.__qualname__ = qualname
        return wrapper

    names = globals()
    for name in __all__:
        obj = names[name]
        if type(obj).__name__ == "builtin_function_or_method":
            signature = _signatures.signature(obj.__doc__, name)
            if signature is not None:
                names[name] = wrap(obj, signature, name)
        elif isinstance(obj, type) and not issubclass(obj, BaseException):
            init = vars(obj).get("__init__")
            signature = _signatures.signature(getattr(init, "__doc__", None), "__init__", True)
            if signature is not None:
                obj.__signature__ = signature
            for member_name, member in list(vars(obj).items()):
                if member_name.startswith("_"):
                    continue
                qualname = f"{obj.__name__}.{member_name}"
                if isinstance(member, staticmethod):
                    native = member.__func__
                    signature = _signatures.signature(native.__doc__, member_name)
                    if signature is not None:
                        setattr(obj, member_name, staticmethod(wrap(native, signature, qualname)))
                elif type(member).__name__ == "instancemethod":
                    native = member.__func__
                    signature = _signatures.signature(native.__doc__, member_name)
                    if signature is not None:
                        setattr(obj, member_name, wrap(native, signature, qualname))


_give_signatures()
