#!/usr/bin/python3
"""Writes the MAT-file and HDF5 fixtures of Oscilab's reader tests with SciPy and h5py.

Usage: write_mat_hdf5.py SPEC.json. The spec (written by the test) says which file to write:
  {"format": "mat5" | "mat73" | "hdf5", "path": "...", "compress": bool, "userblock": int,
   "variables": [{"name": "V1" or "/group/data", "dtype": "float64", "shape": [rows, cols],
                  "values": [... row-major ...] or "amplitude": A (a sine instead),
                  "byteorder": "<" or ">",
                  "attrs": {"dT": 0.001, "units": "m/s"}}],
   "groups": [{"path": "/g", "attrs": {...}}],
   "special": [{"name": "...", "kind": "cell" | "struct" | "char" | "sparse" | "complex" |
                "3d" | "empty" | "logical" | "compound" | "string" | "vlen" | "scalar" |
                "enum" | "soft" | "external" | "cycle"}]}
A MAT variable's shape is MATLAB's (rows, cols); an HDF5 dataset's is the dataset's own.
"""
import json
import sys

import numpy as np


def array_of(variable):
    if "values" in variable:
        values = np.array(variable["values"], dtype=np.float64)
    else:  # "sine": a sine of `amplitude` and period 97 samples (benchmark files)
        count = int(np.prod(variable["shape"]))
        values = variable["amplitude"] * np.sin(2 * np.pi * np.arange(count) / 97.0)
    dtype = np.dtype(variable.get("byteorder", "=") + np.dtype(variable["dtype"]).str[1:])
    if variable["dtype"] == "bool":
        return values.astype(bool).reshape(variable["shape"])
    return values.astype(dtype).reshape(variable["shape"])


def write_mat5(spec):
    import scipy.io
    import scipy.sparse
    contents = {}
    for variable in spec.get("variables", []):
        contents[variable["name"]] = array_of(variable)
    for special in spec.get("special", []):
        kind = special["kind"]
        contents[special["name"]] = {
            "cell": lambda: np.array([[np.ones(3), "text"]], dtype=object),
            "struct": lambda: {"a": 1.0, "b": np.arange(3.0)},
            "char": lambda: "some text",
            "sparse": lambda: scipy.sparse.csc_matrix(np.eye(4)),
            "complex": lambda: np.array([[1 + 2j, 3 - 1j, 0.5j]]),
            "3d": lambda: np.zeros((2, 3, 4)),
            "empty": lambda: np.zeros((0, 0)),
            "logical": lambda: np.array([[True, False, True, True]]),
        }[kind]()
    scipy.io.savemat(spec["path"], contents, do_compression=spec.get("compress", False),
                     oned_as="row")


def mat73_header():
    # "MAT-File Format" (MathWorks), v7.3: a 512-byte user block whose first 128 bytes are the
    # Level 5 header: 116 bytes of text, 8 bytes of subsystem offset, version 0x0200, "IM".
    text = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Wed Nov 25 07:00:00 2026 HDF5 schema 1.00 ."
    header = text.ljust(116, b" ") + b"\x00" * 8 + b"\x00\x02" + b"IM"
    return header.ljust(512, b"\x00")


def write_mat73(spec):
    import h5py
    with h5py.File(spec["path"], "w", userblock_size=512, libver="earliest") as f:
        for variable in spec.get("variables", []):
            values = array_of(variable)
            # MATLAB stores column-major: a rows x cols matrix is a cols x rows dataset.
            dataset = f.create_dataset(variable["name"], data=values.T)
            matlab_class = {"float64": "double", "float32": "single", "bool": "logical"}.get(
                variable["dtype"], variable["dtype"])
            if variable["dtype"] == "bool":
                dataset[...] = values.T.astype(np.uint8)
            dataset.attrs.create("MATLAB_class", np.bytes_(matlab_class))
        for special in spec.get("special", []):
            name, kind = special["name"], special["kind"]
            if kind == "char":  # MATLAB's chars: uint16 code units
                dataset = f.create_dataset(name, data=np.frombuffer(b"hi", np.uint8).astype(
                    np.uint16).reshape(2, 1))
                dataset.attrs.create("MATLAB_class", np.bytes_("char"))
            elif kind == "struct":  # a group
                group = f.create_group(name)
                group.attrs.create("MATLAB_class", np.bytes_("struct"))
                group.create_dataset("a", data=np.ones((1, 1)))
            elif kind == "empty":  # MATLAB stores an empty array's dimensions as its values
                dataset = f.create_dataset(name, data=np.array([0, 0], dtype=np.uint64))
                dataset.attrs.create("MATLAB_class", np.bytes_("double"))
                dataset.attrs.create("MATLAB_empty", np.uint8(1))
            elif kind == "plain":  # a dataset without MATLAB_class
                f.create_dataset(name, data=np.ones(3))
            else:
                raise ValueError(kind)
    with open(spec["path"], "r+b") as f:
        f.write(mat73_header())


def write_hdf5(spec):
    import h5py
    userblock = spec.get("userblock", 0)
    with h5py.File(spec["path"], "w", userblock_size=userblock) as f:
        for group in spec.get("groups", []):
            g = f.require_group(group["path"])
            for key, value in group.get("attrs", {}).items():
                g.attrs[key] = value
        for variable in spec.get("variables", []):
            dataset = f.create_dataset(variable["name"], data=array_of(variable),
                                       compression="gzip" if spec.get("compress") else None)
            for key, value in variable.get("attrs", {}).items():
                dataset.attrs[key] = value
        for special in spec.get("special", []):
            name, kind = special["name"], special["kind"]
            if kind == "compound":
                f.create_dataset(name, data=np.zeros(4, dtype=[("a", "f8"), ("b", "i4")]))
            elif kind == "string":
                f.create_dataset(name, data=np.array([b"ab", b"cd"]))
            elif kind == "vlen":
                dataset = f.create_dataset(name, (2,), dtype=h5py.vlen_dtype(np.float64))
                dataset[0] = np.arange(3.0)
            elif kind == "3d":
                f.create_dataset(name, data=np.zeros((2, 3, 4)))
            elif kind == "scalar":
                f.create_dataset(name, data=1.5)
            elif kind == "enum":
                f.create_dataset(name, data=np.array([True, False, True]))
            elif kind == "soft":
                f[name] = h5py.SoftLink(special["target"])
            elif kind == "external":
                f[name] = h5py.ExternalLink("elsewhere.h5", "/data")
            elif kind == "empty":
                f.create_dataset(name, data=np.zeros(0))
            elif kind == "external_data":  # raw data in another file
                f.create_dataset(name, (4,), dtype="f8", external=[("other.bin", 0, 32)])
            elif kind == "cycle":
                f[name] = f[special["target"]]
            else:
                raise ValueError(kind)


def main():
    with open(sys.argv[1]) as f:
        spec = json.load(f)
    {"mat5": write_mat5, "mat73": write_mat73, "hdf5": write_hdf5}[spec["format"]](spec)


if __name__ == "__main__":
    main()
