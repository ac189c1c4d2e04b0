"""The compiled part of oscilab (pybind11); import oscilab instead."""
