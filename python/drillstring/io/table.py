"""Tables of numbers written without pandas (whose import alone costs about 0.3 s of CPU time):
Parquet through pyarrow, with the metadata from which ``pandas.read_parquet`` rebuilds the index,
and CSV as ``DataFrame.to_csv(float_format=...)`` writes it. A table is an index (its name and
values) and named columns of equal length, each float64, int64 or bool."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import numpy as np

__all__ = ["csv_text", "write_parquet", "read_parquet_frame", "frame_to_parquet"]

_KINDS = {"f": "float64", "i": "int64", "b": "bool"}


def _arrays(index: tuple[str, Any], columns: Mapping[str, Any]) -> dict[str, np.ndarray]:
    """The index and the columns as 1-D arrays of one length, the index first; a ``TypeError``
    for another dtype than float64, int64 or bool, a ``ValueError`` for unequal lengths."""
    out = {index[0]: np.asarray(index[1])}
    out.update({name: np.asarray(values) for name, values in columns.items()})
    for name, values in out.items():
        if values.ndim != 1 or values.dtype.kind not in _KINDS:
            raise TypeError(f"table column {name!r}: {values.dtype} of shape {values.shape}, expected 1-D "
                            "float64, int64 or bool")
        if values.dtype.kind != "b" and values.dtype.itemsize != 8:
            out[name] = values.astype(_KINDS[values.dtype.kind])
    lengths = {len(values) for values in out.values()}
    if len(lengths) > 1:
        raise ValueError(f"table columns of unequal lengths {sorted(lengths)}")
    return out


def _pandas_metadata(arrays: Mapping[str, np.ndarray], index: str) -> bytes:
    """The ``pandas`` schema metadata pyarrow writes for a frame with this index and columns."""
    import pyarrow

    def entry(name: str) -> dict[str, Any]:
        kind = _KINDS[arrays[name].dtype.kind]
        return {"name": name, "field_name": name, "pandas_type": kind, "numpy_type": kind, "metadata": None}

    try:
        from importlib.metadata import version

        pandas_version = version("pandas")
    except Exception:  # pandas not installed: the file is read by pyarrow alone
        pandas_version = "2.0.0"
    meta = {
        "index_columns": [index],
        "column_indexes": [{"name": None, "field_name": None, "pandas_type": "unicode", "numpy_type": "str",
                            "metadata": {"encoding": "UTF-8"}}],
        "columns": [entry(name) for name in arrays if name != index] + [entry(index)],
        "attributes": {},
        "creator": {"library": "pyarrow", "version": pyarrow.__version__},
        "pandas_version": pandas_version,
    }
    return json.dumps(meta).encode("utf-8")


def _arrow(pa: Any, values: np.ndarray) -> Any:
    """``values`` as a pyarrow array, from its buffer (``pyarrow.array`` would import pandas to
    look at it first); NaN as null, as pandas hands a float column to pyarrow."""
    if values.dtype.kind == "b":
        bits = np.packbits(values, bitorder="little")
        return pa.Array.from_buffers(pa.bool_(), len(values), [None, pa.py_buffer(bits)])
    values = np.ascontiguousarray(values)
    kind = pa.float64() if values.dtype.kind == "f" else pa.int64()
    missing = np.isnan(values) if values.dtype.kind == "f" else None
    if missing is not None and missing.any():
        valid = pa.py_buffer(np.packbits(~missing, bitorder="little"))
        return pa.Array.from_buffers(kind, len(values), [valid, pa.py_buffer(values)], null_count=int(missing.sum()))
    return pa.Array.from_buffers(kind, len(values), [None, pa.py_buffer(values)])


def write_parquet(target: Any, index: tuple[str, Any], columns: Mapping[str, Any]) -> None:
    """Writes the table to ``target`` (a path or a binary file) as Parquet (pyarrow's defaults:
    snappy compression), as ``DataFrame.to_parquet`` writes the frame indexed by ``index`` (NaN
    as null): ``pandas.read_parquet`` gives that frame back. pandas is not imported."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    arrays = _arrays(index, columns)
    names = [name for name in arrays if name != index[0]] + [index[0]]
    table = pa.Table.from_arrays([_arrow(pa, arrays[name]) for name in names], names=names)
    table = table.replace_schema_metadata({b"pandas": _pandas_metadata(arrays, index[0])})
    pq.write_table(table, target)


def read_parquet_frame(source: Any) -> Any:
    """The ``DataFrame`` in the Parquet ``source`` (a path, a binary file or ``bytes``), as
    ``pandas.read_parquet`` gives it, read and converted on the calling thread.

    ``pandas.read_parquet`` reads through pyarrow's dataset scanner and thread pools; a process
    that exits soon after can then abort in pyarrow's teardown ("terminate called without an
    active exception", apache/arrow#34314). No thread is started here."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    if isinstance(source, (bytes, bytearray, memoryview)):
        source = pa.BufferReader(bytes(source))
    table = pq.ParquetFile(source, pre_buffer=False).read(use_threads=False)
    return table.to_pandas(use_threads=False)


def frame_to_parquet(frame: Any, target: Any = None, *, index: Any = None) -> Any:
    """Writes ``frame`` as ``DataFrame.to_parquet(target, index=index)`` does (pyarrow's
    defaults: snappy compression, the pandas metadata), on the calling thread (see
    :func:`read_parquet_frame`); with ``target=None`` returns the file's bytes."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.Table.from_pandas(frame, preserve_index=index, nthreads=1)
    if target is not None:
        pq.write_table(table, target)
        return None
    sink = pa.BufferOutputStream()
    pq.write_table(table, sink)
    return sink.getvalue().to_pybytes()


def _cell(value: Any, float_format: str) -> str:
    if isinstance(value, (bool, np.bool_)):
        return "True" if value else "False"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return "" if value != value else float_format % value  # NaN: an empty cell


def csv_text(index: tuple[str, Any], columns: Mapping[str, Any], float_format: str = "%.10g") -> str:
    """The table as ``DataFrame.to_csv(float_format=float_format)`` of the frame indexed by
    ``index`` writes it: a header line, then one line per row, the index first; floats by
    ``float_format``, NaN as an empty cell, integers and booleans as Python writes them."""
    arrays = _arrays(index, columns)
    lines = [",".join(arrays)]
    if all(values.dtype.kind == "f" for values in arrays.values()):
        # the common case, all floats: one format per row (NaN rows cell by cell)
        rows = np.column_stack(list(arrays.values())) if arrays else np.empty((0, 0))
        row_format = ",".join([float_format] * rows.shape[1])
        finite: list[bool] = np.isfinite(rows.sum(axis=1)).tolist() if rows.size else []
        for row, plain in zip(rows.tolist(), finite):
            lines.append(row_format % tuple(row) if plain else ",".join(_cell(v, float_format) for v in row))
    else:
        for row in zip(*(values.tolist() for values in arrays.values())):
            lines.append(",".join(_cell(v, float_format) for v in row))
    return "\n".join(lines) + "\n"

