"""Tables written without pandas (``drillstring.io.table``) against pandas writing the same frame:
the CSV text byte for byte, and the Parquet file read back by pandas as the same frame (index,
columns, dtypes, values bit for bit), for any values, NaN, infinities and signed zeros included."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from drillstring.io.table import csv_text, write_parquet

FLOATS = st.floats(allow_nan=True, allow_infinity=True, width=64)


@st.composite
def tables(draw: st.DrawFn) -> tuple[tuple[str, np.ndarray], dict[str, np.ndarray]]:
    rows = draw(st.integers(0, 12))
    names = draw(st.lists(st.sampled_from(["surface_rpm", "bit_rpm", "rop", "weight_on_bit", "x"]), min_size=1,
                          max_size=4, unique=True))
    columns = {}
    for name in names:
        kind = draw(st.sampled_from(["float", "float", "int", "bool"]))
        if kind == "float":
            columns[name] = draw(arrays(np.float64, rows, elements=FLOATS))
        elif kind == "int":
            columns[name] = draw(arrays(np.int64, rows, elements=st.integers(-(2**62), 2**62)))
        else:
            columns[name] = draw(arrays(np.bool_, rows))
    t = draw(arrays(np.float64, rows, elements=st.floats(-1e9, 1e9)))
    return ("t", t), columns


def _frame(index: tuple[str, np.ndarray], columns: dict[str, np.ndarray]) -> pd.DataFrame:
    return pd.DataFrame(columns, index=pd.Index(index[1], name=index[0]))


@settings(max_examples=60, deadline=None)
@given(tables(), st.sampled_from(["%.10g", "%.17g", "%.3f"]))
def test_csv_is_what_pandas_writes(table: tuple[tuple[str, np.ndarray], dict[str, np.ndarray]],
                                   float_format: str) -> None:
    index, columns = table
    assert csv_text(index, columns, float_format) == _frame(index, columns).to_csv(float_format=float_format)


@settings(max_examples=30, deadline=None)
@given(tables())
def test_parquet_reads_back_in_pandas_as_the_frame(tmp_path_factory: pytest.TempPathFactory,
                                                   table: tuple[tuple[str, np.ndarray], dict[str, np.ndarray]]) -> None:
    index, columns = table
    path = tmp_path_factory.mktemp("table") / "series.parquet"
    write_parquet(path, index, columns)
    pd.testing.assert_frame_equal(pd.read_parquet(path), _frame(index, columns), check_exact=True)
    # and as pandas writes it: NaN as null, the same schema and metadata
    theirs = path.with_name("pandas.parquet")
    _frame(index, columns).to_parquet(theirs)
    assert pq.read_table(path).equals(pq.read_table(theirs), check_metadata=True)


def test_writing_parquet_does_not_import_pandas(tmp_path: Path) -> None:
    code = ("import sys, numpy as np\n"
            "from drillstring.io.table import write_parquet\n"
            "columns = {'a': np.array([1.0, np.nan, 2.0]), 'b': np.ones(3, bool)}\n"
            "write_parquet(sys.argv[1], ('t', np.arange(3.0)), columns)\n"
            "print('pandas' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code, str(tmp_path / "x.parquet")], capture_output=True,
                          text=True, check=True)
    assert done.stdout.strip() == "False", done.stderr
    assert pd.read_parquet(tmp_path / "x.parquet")["a"].isna().tolist() == [False, True, False]


def test_bad_columns_are_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="unequal lengths"):
        csv_text(("t", np.zeros(3)), {"a": np.zeros(2)})
    with pytest.raises(TypeError, match="'a'"):
        write_parquet(tmp_path / "x.parquet", ("t", np.zeros(2)), {"a": np.array(["x", "y"])})


# --------------------------------------------------------------------------- Parquet on the calling thread


@settings(max_examples=40, deadline=None)
@given(tables(), st.booleans())
def test_a_frame_written_and_read_on_the_calling_thread_is_the_frame_pandas_reads(
        table: tuple[tuple[str, np.ndarray], dict[str, np.ndarray]], keep_index: bool) -> None:
    from drillstring.io.table import frame_to_parquet, read_parquet_frame

    index, columns = table
    frame = pd.DataFrame(columns, index=pd.Index(index[1], name=index[0]))
    data = frame_to_parquet(frame, index=None if keep_index else False)
    expected = pd.read_parquet(__import__("io").BytesIO(data))
    pd.testing.assert_frame_equal(read_parquet_frame(data), expected, check_exact=True)
    pd.testing.assert_frame_equal(expected, frame if keep_index else frame.reset_index(drop=True), check_exact=True)


@pytest.mark.skipif(not Path("/proc/self/task").is_dir(), reason="counts threads in /proc")
def test_parquet_is_read_and_written_without_starting_a_thread(tmp_path: Path) -> None:
    # pandas.read_parquet starts pyarrow's thread pools, and a process exiting soon after can
    # abort in their teardown ("terminate called without an active exception"): a resumed map
    # that refused a FIFO in its store did, once in a few hundred runs. The store's reads and
    # writes start no thread; pandas's own read, checked last, shows the count can move.
    code = (
        "import os, pandas as pd, numpy as np\n"
        "from drillstring.io.table import frame_to_parquet, read_parquet_frame\n"
        "def threads(): return len(os.listdir('/proc/self/task'))\n"
        "frame = pd.DataFrame({'a': np.arange(50000.0), 'b': np.arange(50000)})\n"
        "before = threads()\n"
        "data = frame_to_parquet(frame)\n"
        "frame_to_parquet(frame, 'f.parquet')\n"
        "assert read_parquet_frame(data).equals(frame) and read_parquet_frame('f.parquet').equals(frame)\n"
        "ours = threads()\n"
        "import io; pd.read_parquet(io.BytesIO(data))\n"
        "print(before, ours, threads())\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    before, ours, theirs = map(int, done.stdout.split())
    assert ours == before, (before, ours)
    assert theirs > before, "the check cannot see pyarrow's threads here"
