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
    analyze,
    describe_recording,
    diagnose,
    draft_sidecar,
    fit,
    hbm_branch,
    live,
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
    "analyze",
    "describe_recording",
    "diagnose",
    "draft_sidecar",
    "fit",
    "hbm_branch",
    "live",
    "prepare_fit",
    "read_recording",
    "simulate",
    "to_dataframe",
    "virtual_rig",
    "write_recording",
]


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
    as the class's __signature__."""
    import functools

    from . import _signatures

    def wrap(native, signature, qualname):
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
