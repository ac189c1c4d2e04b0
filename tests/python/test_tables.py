"""One schema per output table: the CSV header of `analyze --edc` and `--cycles`, the keys of
Analysis.edc and Analysis.cycles, the variables of `export --edc-mat` and the column tables of
docs/contracts.md §3 name the same columns in the same order, each stored as its kind says."""

import pytest

import oscilab
from conftest import SOURCE_DIR, STEPPED, run_cli

scipy_io = pytest.importorskip("scipy.io")

# How each kind of docs/contracts.md is stored: the MATLAB class and the NumPy dtype kind.
MAT_CLASS = {"real": "double", "integer": "double", "flag": "logical", "text": "cell"}
NUMPY_KIND = {"real": "f", "integer": "i", "flag": "b", "text": "U"}


def contract_columns(heading):
    """(name, unit, kind) of each row of the first table after `heading` in docs/contracts.md."""
    lines = (SOURCE_DIR / "docs" / "contracts.md").read_text().splitlines()
    start = lines.index(heading)
    rows = []
    for line in lines[start + 1:]:
        if line.startswith("#"):
            break
        if line.startswith("|"):
            rows.append([cell.strip() for cell in line.strip("|").split(" | ")])
        elif rows:
            break
    assert rows[0] == ["column", "unit", "kind", "meaning"], rows[0]
    return [(name.strip("`"), unit, kind) for name, unit, kind, *_ in rows[2:]]


def csv_header(path):
    with open(path) as f:
        return f.readline().rstrip("\n").split(",")


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("tables")
    run_cli("analyze", *STEPPED, "--edc", out / "edc.csv", "--cycles", out / "cycles.csv")
    run_cli("export", *STEPPED, "--edc-mat", out / "edc.mat")
    return out


def test_edc_csv_python_mat_and_docs_name_the_same_columns_in_one_order(written, py_analysis):
    documented = contract_columns("### EDC table (`analyze --edc`)")
    names = [name for name, _, _ in documented]
    assert csv_header(written / "edc.csv") == names
    assert list(py_analysis.edc) == names
    variables = scipy_io.whosmat(written / "edc.mat")  # in the file's order
    assert [name for name, _, _ in variables] == names
    levels = len(py_analysis.edc["f0_n"])
    for (name, unit, kind), (_, shape, mat_class) in zip(documented, variables):
        assert mat_class == MAT_CLASS[kind], (name, mat_class)
        assert shape == (levels, 1), name
        assert py_analysis.edc[name].dtype.kind == NUMPY_KIND[kind], name


def test_cycles_csv_python_and_docs_name_the_same_columns_in_one_order(written, py_analysis):
    documented = contract_columns("### Cycle table (`analyze --cycles`)")
    names = [name for name, _, _ in documented]
    assert csv_header(written / "cycles.csv") == names
    assert list(py_analysis.cycles) == names
    for name, _, kind in documented:
        assert py_analysis.cycles[name].dtype.kind == NUMPY_KIND[kind], name


def test_the_mat_files_columns_hold_the_tables_values(written, py_analysis):
    mat = scipy_io.loadmat(written / "edc.mat")
    edc = py_analysis.edc
    for name, column in edc.items():
        stored = mat[name].ravel()
        if column.dtype.kind == "U":
            assert [str(cell.item()) if cell.size else "" for cell in stored] == column.tolist()
        else:
            assert stored.astype(column.dtype).tolist() == column.tolist(), name
