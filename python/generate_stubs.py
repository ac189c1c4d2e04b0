#!/usr/bin/env python3
"""Writes oscilab/__init__.pyi, the package's type stubs, from the built module itself: every
public name of oscilab.__all__, each function's and method's signature as pybind11 states it
(oscilab/_signatures.py gives the arguments the bindings take as `object` their real types),
properties with their types, the exception family.

    PYTHONPATH=build/python python3 python/generate_stubs.py            # rewrite the stubs
    PYTHONPATH=build/python python3 python/generate_stubs.py --check    # exit 1 if they differ

tests/python/test_stubs.py runs the check, so the checked-in stubs always match the module.
"""

import argparse
import inspect
import sys
from pathlib import Path

STUBS = Path(__file__).resolve().parent / "oscilab" / "__init__.pyi"

HEADER = '''"""Type stubs of the oscilab package, generated from the module by
python/generate_stubs.py (do not edit: run it after changing a binding; tests/python/test_stubs.py
checks them)."""

import os
from typing import Any, Callable, Iterable, Mapping

from numpy.typing import ArrayLike, NDArray
import numpy
'''


def parameter_text(parameter):
    text = parameter.name
    if parameter.kind is inspect.Parameter.VAR_POSITIONAL:
        text = "*" + text
    elif parameter.kind is inspect.Parameter.VAR_KEYWORD:
        text = "**" + text
    annotation = parameter.annotation
    if annotation is not inspect.Parameter.empty and parameter.name != "self":
        text += ": " + annotation
    if parameter.default is not inspect.Parameter.empty:
        text += " = " + repr(parameter.default)
    return text


def signature_text(signature):
    parts = []
    seen_keyword_only = False
    positional_only = False
    for parameter in signature.parameters.values():
        if parameter.kind is inspect.Parameter.POSITIONAL_ONLY:
            positional_only = True
        elif positional_only:
            parts.append("/")
            positional_only = False
        if parameter.kind is inspect.Parameter.KEYWORD_ONLY and not seen_keyword_only:
            parts.append("*")
        if parameter.kind in (inspect.Parameter.KEYWORD_ONLY, inspect.Parameter.VAR_POSITIONAL):
            seen_keyword_only = True
        parts.append(parameter_text(parameter))
    if positional_only:
        parts.append("/")
    returns = signature.return_annotation
    returns = "Any" if returns is inspect.Signature.empty else returns
    return "(" + ", ".join(parts) + ") -> " + returns


def python_function_signature(function):
    """A plain Python function's signature, its unannotated arguments as Any."""
    signature = inspect.signature(function)
    parameters = [p if p.annotation is not p.empty or p.name == "self"
                  else p.replace(annotation="Any") for p in signature.parameters.values()]
    return signature.replace(parameters=parameters,
                             return_annotation=signature.return_annotation
                             if signature.return_annotation is not signature.empty else "Any")


def function_signature(function, name, signatures):
    if getattr(function, "__signature__", None) is not None:
        return function.__signature__
    native = getattr(function, "__wrapped__", function)
    parsed = signatures.signature(native.__doc__, name)
    if parsed is not None:
        return parsed
    return python_function_signature(function)


def class_lines(cls, signatures):
    bases = [b.__name__ for b in cls.__bases__ if b.__name__ not in ("pybind11_object", "object")]
    lines = [f"class {cls.__name__}{'(' + ', '.join(bases) + ')' if bases else ''}:"]
    body = []
    if issubclass(cls, BaseException):
        return lines + ["    ..."]
    init = vars(cls).get("__init__")
    init_signature = signatures.signature(getattr(init, "__doc__", None), "__init__")
    if init_signature is not None:
        body.append(f"    def __init__{signature_text(init_signature)}: ...")
    for name, member in vars(cls).items():
        if name in ("__init__", "__repr__", "__doc__", "__module__") or (
                name.startswith("_") and not name.startswith("__")):
            continue
        if isinstance(member, property):
            fget = getattr(member.fget, "__wrapped__", member.fget)
            parsed = signatures.parse(fget.__doc__, "")
            returns = signatures.python_type(parsed[1]) if parsed else "Any"
            body.append("    @property")
            body.append(f"    def {name}(self) -> {returns}: ...")
            if member.fset is not None:
                body.append(f"    @{name}.setter")
                body.append(f"    def {name}(self, value: Any) -> None: ...")
        elif isinstance(member, staticmethod):
            signature = function_signature(member.__func__, name, signatures)
            body.append("    @staticmethod")
            body.append(f"    def {name}{signature_text(signature)}: ...")
        elif name == "__eq__":  # returns NotImplemented for other types: the C++ side's object
            body.append("    def __eq__(self, other: object) -> bool: ...")
        elif callable(member):
            signature = function_signature(member, name, signatures)
            body.append(f"    def {name}{signature_text(signature)}: ...")
    return lines + (body or ["    ..."])


def stubs_text():
    # The built package (PYTHONPATH), not python/oscilab beside this script, which has no
    # extension.
    here = STUBS.parent.parent
    sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != here]
    import oscilab
    from oscilab import _signatures as signatures

    lines = [HEADER]
    for alias, text in signatures.ALIASES.items():
        lines.append(f"{alias} = {text}")
    lines.append("")
    lines.append("__version__: str")
    lines.append("__all__ = [" + ", ".join(repr(n) for n in oscilab.__all__) + "]")
    for name in oscilab.__all__:
        obj = getattr(oscilab, name)
        lines.append("")
        if inspect.isclass(obj):
            lines.append("")
            lines.extend(class_lines(obj, signatures))
            lines.append("")
        else:
            signature = function_signature(obj, name, signatures)
            lines.append(f"def {name}{signature_text(signature)}: ...")
    text = "\n".join(lines).rstrip() + "\n"
    while "\n\n\n\n" in text:
        text = text.replace("\n\n\n\n", "\n\n\n")
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true",
                        help="compare with the checked-in stubs instead of writing them")
    parser.add_argument("--out", type=Path, default=STUBS)
    args = parser.parse_args()
    text = stubs_text()
    if args.check:
        if args.out.read_text() != text:
            print(f"{args.out}: differs from the module's signatures; run {sys.argv[0]}",
                  file=sys.stderr)
            return 1
        return 0
    args.out.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
