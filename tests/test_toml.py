"""TOML: the line of a key, found in tomlkit's document of the file however the key is written (a
``[table]``, a dotted key, an inline table, a quoted key, an array of tables), and the documents
the package writes, read back by the standard library's parser."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from _cli import one_line_error, run_cli
from hypothesis import given, settings
from hypothesis import strategies as st

import drillstring as ds
from drillstring.drilling import load_drill_config
from drillstring.errors import ValidationError
from drillstring.io.toml import key_line, toml_line

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

#: Lines around the key: comments, blank lines, other keys, a multi-line array, and a multi-line
#: string whose text looks like the key and its table (a scanner of lines would take it for them).
FILLERS = ("", "# c = 7 in a comment", "k{n} = 1", "m{n} = [\n  1,\n  2,\n]", 'd{n} = """\n[a.b]\nc = 0\n"""')
filler = st.lists(st.sampled_from(FILLERS), max_size=4)

#: The ways of writing ``a.b.c = 7``: (the table header it needs or None, the key's line).
STYLES = {
    "table": ("[a.b]", "c = 7"),
    "quoted key": ("[a.b]", '"c" = 7'),
    "dotted key in a table": ("[a]", "b.c = 7"),
    "quoted dotted key": ("[a]", "\"b\" . 'c' = 7"),
    "inline table": ("[a]", "b = {x = 0, c = 7}"),
    "dotted key at the top": (None, "a.b.c = 7"),
    "nested inline tables at the top": (None, "a = {b = {c = 7}}"),
}


def _lines(items: list[str], prefix: str) -> list[str]:
    """The filler entries as lines, each key named apart by ``prefix`` and its place."""
    return "\n".join(item.format(n=f"{prefix}{i}") for i, item in enumerate(items)).split("\n") if items else []


@settings(max_examples=150, deadline=None)
@given(style=st.sampled_from(sorted(STYLES)), lead=filler, inside=filler, after=filler)
def test_the_line_of_a_key_is_where_it_is_written_however_it_is_written(
    style: str, lead: list[str], inside: list[str], after: list[str]
) -> None:
    header, statement = STYLES[style]
    lines = _lines(lead, "t")
    if header is not None:
        lines += [header, *_lines(inside, "u")]
    lines.append(statement)
    expected = len(lines)
    lines += _lines(after, "v")
    lines += ["[z]", "c = 1", "[y.b]", "c = 2"]  # the same key name in other tables
    text = "\n".join(lines) + "\n"
    assert tomllib.loads(text)["a"]["b"]["c"] == 7  # the document says what it is meant to
    assert key_line(text, "a.b.c") == expected, text


@settings(max_examples=100, deadline=None)
@given(sections=st.lists(st.tuples(filler, st.booleans(), filler), min_size=1, max_size=4), data=st.data())
def test_the_line_of_a_key_in_an_array_of_tables_is_its_table_s(
    sections: list[tuple[list[str], bool, list[str]]], data: st.DataObject
) -> None:
    """``sections[i].length``: the line of ``length`` in the i-th ``[[sections]]``, or of that
    table's header when it has no ``length``."""
    lines = ["# a configuration", "damping_rate = 0.1"]
    where = []
    for i, (before, has_length, after) in enumerate(sections):
        lines += ["", "[[sections]]"]
        header = len(lines)
        lines += [f'name = "s{i}"', *_lines(before, f"b{i}_")]
        if has_length:
            lines.append(f"length = {100.0 * (i + 1)!r}")
        where.append(len(lines) if has_length else header)
        lines += _lines(after, f"a{i}_")
    text = "\n".join(lines) + "\n"
    index = data.draw(st.integers(0, len(sections) - 1))
    parsed = tomllib.loads(text)["sections"][index]
    assert ("length" in parsed) == sections[index][1]
    assert key_line(text, f"sections[{index}].length") == where[index], text
    # no such table: the array's line, its first table's header
    assert key_line(text, f"sections[{len(sections)}].length") == 4


def test_the_line_of_an_element_of_a_multi_line_array_and_of_what_is_not_there() -> None:
    text = "[well]\nmd = [\n  0.0,\n  100.0,\n  200.0,\n]\ninclination_deg = 3.0\n"
    assert [key_line(text, f"well.md[{i}]") for i in range(3)] == [3, 4, 5]
    assert key_line(text, "well.md[7]") == 2  # past its end: the array's key
    assert key_line(text, "well.azimuth_deg") == 1  # not set: its table
    assert key_line(text, "bit.radius") is None and key_line(text, "") is None
    assert key_line("[well\n", "well.md") is None  # not TOML


def test_a_table_written_in_parts_is_found_at_the_part_that_holds_the_key() -> None:
    text = "[a.b]\nx = 1\n[c]\ny = 1\n[a.e]\nz = 2\n[a]\nw = 3\n[[s]]\n[[s.t]]\nu = 1\n[[s]]\n"
    assert tomllib.loads(text)["a"] == {"b": {"x": 1}, "e": {"z": 2}, "w": 3}
    cases = {"a.b.x": 2, "a.e.z": 6, "a.w": 8, "a.q": 7, "a.b.q": 1, "s[0].t[0].u": 11, "s[1].t": 12, "s[1].v": 12}
    assert {field: key_line(text, field) for field in cases} == cases


GOOD = """\
# a string of two sections
damping_rate = 0.0
numerics = {cells = 100}

[[sections]]
name = "pipe"
length = 1000.0
outer_diameter = 0.127
inner_diameter = 0.1086

[[sections]]  # the collars
name = "collars"
length = 100.0
outer_diameter = 0.17
inner_diameter = 0.07

[top_drive]
rpm = 40.0
controller.type = "pi"
"controller".kp = 1000.0
"""


@pytest.mark.parametrize(
    ("old", "new", "field", "line"),
    [
        ("numerics = {cells = 100}", "numerics = {cells = -100}", "numerics.cells", 3),  # an inline table
        ("length = 100.0", "length = -100.0", "sections[1].length", 13),  # an array of tables
        ('"controller".kp = 1000.0', '"controller".kp = -1000.0', "top_drive.controller.kp", 20),  # quoted, dotted
        ("rpm = 40.0", '"rpm" = "fast"', "top_drive.rpm", 18),  # a quoted key
        ('controller.type = "pi"', 'controller.type = "fuzzy"', "top_drive.controller.type", 19),  # a dotted key
    ],
)
def test_a_bad_value_of_a_configuration_is_named_at_its_line(
    tmp_path: Path, old: str, new: str, field: str, line: int
) -> None:
    assert old in GOOD and load_drill_config(_write(tmp_path, GOOD)).numerics.cells == 100
    path = _write(tmp_path, GOOD.replace(old, new, 1))
    with pytest.raises(ValidationError) as info:
        load_drill_config(path)
    assert (info.value.field, info.value.line) == (field, line), str(info.value)
    assert str(info.value).startswith(f"{path}, line {line}: invalid {field}")
    assert toml_line(path, field) == line


def test_a_bad_parameter_and_solver_option_are_named_at_their_lines(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = '# a rod\n[parameters]\nomega = 2.0\n"length" = -1.0\n\n[solver]\nmodes = 2\nt_end = "1 s"\n'
    path = _write(tmp_path, text)
    with pytest.raises(ValidationError) as info:
        ds.load(path)
    assert (info.value.field, info.value.line) == ("length", 4)
    path.write_text(text.replace("-1.0", "100.0"))
    code, _, err = run_cli(capsys, "simulate", str(path))
    assert code == 2
    one_line_error(err, f"{path}, line 8: invalid solver.t_end")


def test_written_documents_are_read_back_by_the_standard_parser() -> None:
    cfg = load_drill_config(Path(__file__).resolve().parents[1] / "examples" / "s-well-3d.toml")
    cfg = cfg.with_overrides(["sections[0].name=\"pipe \\\"5 in\\\" \\u0085 é\""])
    parsed = tomllib.loads(cfg.to_toml())
    assert parsed["sections"][0]["name"] == 'pipe "5 in" \x85 é'
    assert ds.DrillConfig.from_dict(parsed) == cfg
    params = ds.preset("steel").replace(model="consistent")
    assert ds.Parameters.from_dict(tomllib.loads(params.to_toml())["parameters"]) == params


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    return path
