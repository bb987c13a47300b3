"""Table-driven bad input across every entry point: the Python API (Parameters, simulate,
solve_pde, results), TOML files, the command line and the raw ``drillstring._core`` bindings.

Every case must raise a clear exception of the stated type whose message names the offending
field (Python), or print one line and exit with status 2 (command line) -- never crash, hang or
return garbage. The resource guards (memory budget, step counts) are tested here too.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest

import drillstring as ds
from drillstring import _core
from drillstring.cli import main
from drillstring.errors import SolveError, ValidationError
from drillstring.studies.sweep_axes import expand_axes

P = ds.preset("aluminum")
NAN, INF = math.nan, math.inf
#: An integer too large for a float (float(HUGE) raises OverflowError; 1e400 is inf).
HUGE = 10**400
HUGE_TEXT = str(HUGE)  # "1000...0", 401 digits
#: An array nested deeper than the TOML parser can recurse.
DEEP_TOML = "[parameters]\nlength = " + "[" * 10_000 + "\n"


def _message(exc: BaseException) -> str:
    """The message plus any notes (PyO3 notes the argument that failed to convert)."""
    return " ".join([str(exc), *getattr(exc, "__notes__", [])])


# ------------------------------------------------------------------ Parameters, field by field

PARAMETER_CASES: list[tuple[str, dict[str, Any]]] = []
for _field in ("length", "youngs_modulus", "density", "outer_diameter"):
    for _label, _value in (("nan", NAN), ("inf", INF), ("negative", -1.0), ("zero", 0.0), ("string", "1.0")):
        PARAMETER_CASES.append((f"{_field}-{_label}", {_field: _value}))
PARAMETER_CASES += [
    ("inner_diameter-nan", {"inner_diameter": NAN}),
    ("inner_diameter-negative", {"inner_diameter": -0.01}),
    ("inner_diameter-equal-outer", {"inner_diameter": 0.20}),
    ("inner_diameter-above-outer", {"inner_diameter": 0.30}),
    ("inner_diameter-string", {"inner_diameter": "0.1"}),
    ("poisson_ratio-nan", {"poisson_ratio": NAN}),
    ("poisson_ratio-half", {"poisson_ratio": 0.5}),  # 1 - 2 nu = 0
    ("poisson_ratio-0.7", {"poisson_ratio": 0.7}),
    ("poisson_ratio-minus-one", {"poisson_ratio": -1.0}),
    ("poisson_ratio-bool", {"poisson_ratio": True}),
    ("omega-nan", {"omega": NAN}),
    ("omega-inf", {"omega": -INF}),
    ("omega-string", {"omega": "3.14"}),
    ("initial_velocities-nan", {"initial_velocities": [0.1, NAN]}),
    ("initial_velocities-inf", {"initial_velocities": [INF]}),
    ("initial_velocities-string", {"initial_velocities": "0.1"}),
    ("initial_velocities-none", {"initial_velocities": None}),
    ("initial_velocities-nested", {"initial_velocities": [[0.1]]}),
    ("damping_rate-nan", {"damping_rate": NAN}),
    ("damping_rate-inf", {"damping_rate": INF}),
    ("damping_rate-negative", {"damping_rate": -0.1}),
    ("damping_rate-string", {"damping_rate": "0.5"}),
    ("damping_rate-bool", {"damping_rate": True}),
    ("damping_rate-10**400", {"damping_rate": HUGE}),
    ("k5_variant-unknown", {"k5_variant": "minus"}),
    ("k5_variant-int", {"k5_variant": 2}),
    # integers too large for a float: the same refusal as 1e400, not OverflowError
    ("length-10**400", {"length": HUGE}),
    ("length-minus-10**400", {"length": -HUGE}),
    ("youngs_modulus-10**400", {"youngs_modulus": HUGE}),
    ("inner_diameter-10**400", {"inner_diameter": HUGE}),
    ("poisson_ratio-10**400", {"poisson_ratio": HUGE}),
    ("omega-10**400", {"omega": -HUGE}),
    ("initial_velocities-10**400", {"initial_velocities": [0.1, HUGE]}),
    ("length-10**5000", {"length": 10**5000}),  # beyond repr's 4300-digit limit too
]


@pytest.mark.parametrize("changes", [c for _, c in PARAMETER_CASES], ids=[i for i, _ in PARAMETER_CASES])
def test_bad_parameter_is_refused_naming_the_field(changes: dict[str, Any]) -> None:
    (name,) = changes
    with pytest.raises(ValidationError) as info:
        P.replace(**changes)
    assert info.value.field.split("[")[0] == name
    assert name in str(info.value) and "expected" in str(info.value)
    with pytest.raises(ValidationError) as info:  # the constructor, as well as replace()
        ds.Parameters(**changes)
    assert info.value.field.split("[")[0] == name


def test_an_integer_too_large_for_a_float_is_refused_like_1e400() -> None:
    with pytest.raises(ValidationError) as as_float:
        ds.Parameters(length=1e400)
    with pytest.raises(ValidationError) as as_int:
        ds.Parameters(length=HUGE)
    assert as_int.value.field == as_float.value.field == "length"
    assert as_int.value.allowed == as_float.value.allowed
    # the message stays short: the digit count, not 401 digits
    assert "an integer of 401 digits" in str(as_int.value) and HUGE_TEXT not in str(as_int.value)
    with pytest.raises(ValidationError, match="an integer of 5001 digits"):
        ds.Parameters(length=10**5000)
    # the largest finite floats and integers that fit one are still accepted
    assert ds.Parameters(length=10**300).length == 1e300
    assert ds.Parameters(omega=-(10**308)).omega == -1e308


@pytest.mark.parametrize(
    "changes",
    [{"youngs_modulus": 1e308}, {"omega": 1e200}, {"length": 1e-300}, {"length": 1e300}, {"outer_diameter": 1e100}],
    ids=["E-overflow", "omega-overflow", "length-underflow", "length-overflow", "diameter-overflow"],
)
def test_valid_fields_whose_coefficients_overflow_are_refused(changes: dict[str, Any]) -> None:
    params = P.replace(**changes)  # each field is in range ...
    with pytest.raises(ValidationError) as info:  # ... but the model's coefficients are not finite
        ds.simulate(params, t_end=0.01)
    assert info.value.field == "parameters"
    assert str(next(iter(changes.values()))) in str(info.value) or next(iter(changes)) in str(info.value)


# ------------------------------------------------------------------ solver options

OPTION_CASES: list[tuple[str, Callable[[], Any], type, str]] = [
    ("modes-zero", lambda: ds.simulate(P, modes=0), ValidationError, "modes"),
    ("modes-huge", lambda: ds.simulate(P, modes=10**6), ValidationError, "modes"),
    ("modes-float", lambda: ds.simulate(P, modes=2.5), ValidationError, "modes"),
    ("modes-string", lambda: ds.simulate(P, modes="3"), ValidationError, "modes"),
    ("rigid_mode-string", lambda: ds.simulate(P, rigid_mode="yes"), ValidationError, "rigid_mode"),
    ("rigid_mode-int", lambda: ds.simulate(P, rigid_mode=1), ValidationError, "rigid_mode"),
    ("t_end-zero", lambda: ds.simulate(P, t_end=0.0), ValidationError, "t_end"),
    ("t_end-negative", lambda: ds.simulate(P, t_end=-1.0), ValidationError, "t_end"),
    ("t_end-nan", lambda: ds.simulate(P, t_end=NAN), ValidationError, "t_end"),
    ("t_end-inf", lambda: ds.solve_pde(P, nodes=20, t_end=INF), ValidationError, "t_end"),
    ("t_end-string", lambda: ds.simulate(P, t_end="1"), ValidationError, "t_end"),
    ("t_eval-unsorted", lambda: ds.simulate(P, t_eval=[0.0, 0.5, 0.2]), ValidationError, "t_eval"),
    ("t_eval-beyond-t_end", lambda: ds.simulate(P, t_eval=[0.0, 2.0]), ValidationError, "t_eval"),
    ("t_eval-negative", lambda: ds.solve_pde(P, nodes=20, t_eval=[-0.1, 0.5]), ValidationError, "t_eval"),
    ("t_eval-nan", lambda: ds.simulate(P, t_eval=[0.0, NAN]), ValidationError, "t_eval"),
    ("t_eval-2d", lambda: ds.simulate(P, t_eval=[[0.0, 0.5]]), ValidationError, "t_eval"),
    ("t_eval-strings", lambda: ds.simulate(P, t_eval=["a", "b"]), ValidationError, "t_eval"),
    ("t_eval-string", lambda: ds.simulate(P, t_eval="0.5"), ValidationError, "t_eval"),
    ("t_eval-complex", lambda: ds.simulate(P, t_eval=[0.0, 1j]), ValidationError, "t_eval"),
    ("t_eval-empty", lambda: ds.simulate(P, t_eval=[]), ValidationError, "t_eval"),
    ("rtol-zero", lambda: ds.simulate(P, rtol=0.0), ValidationError, "rtol"),
    ("rtol-negative", lambda: ds.solve_pde(P, nodes=20, rtol=-1e-6), ValidationError, "rtol"),
    ("rtol-one", lambda: ds.simulate(P, rtol=1.0), ValidationError, "rtol"),
    ("atol-zero", lambda: ds.simulate(P, atol=0.0), ValidationError, "atol"),
    ("atol-nan", lambda: ds.simulate(P, atol=NAN), ValidationError, "atol"),
    ("dt-zero", lambda: ds.simulate(P, method="rk4", dt=0.0), ValidationError, "dt"),
    ("dt-negative", lambda: ds.solve_pde(P, nodes=20, method="verlet", dt=-1e-5), ValidationError, "dt"),
    ("dt-above-t_end", lambda: ds.simulate(P, method="central", dt=2.0), ValidationError, "dt"),
    ("samples-one", lambda: ds.simulate(P, samples=1), ValidationError, "samples"),
    ("samples-float", lambda: ds.simulate(P, samples=10.0), ValidationError, "samples"),
    ("method-unknown", lambda: ds.simulate(P, method="euler"), ValidationError, "method"),
    ("method-none", lambda: ds.solve_pde(P, method=None), ValidationError, "method"),
    ("max_steps-zero", lambda: ds.simulate(P, max_steps=0), ValidationError, "max_steps"),
    ("max_steps-negative", lambda: ds.simulate(P, max_steps=-5), ValidationError, "max_steps"),
    ("max_steps-2**70", lambda: ds.simulate(P, max_steps=2**70), ValidationError, "max_steps"),
    ("nonlinear-string", lambda: ds.simulate(P, nonlinear="no"), ValidationError, "nonlinear"),
    ("check-string", lambda: ds.simulate(P, check="x"), ValidationError, "check"),
    ("params-dict", lambda: ds.simulate({"length": 100.0}), ValidationError, "params"),
    ("nodes-two", lambda: ds.solve_pde(P, nodes=2), ValidationError, "nodes"),
    ("nodes-huge", lambda: ds.solve_pde(P, nodes=10**7), ValidationError, "nodes"),
    ("nodes-float", lambda: ds.solve_pde(P, nodes=100.0), ValidationError, "nodes"),
    ("save_field_every-zero", lambda: ds.solve_pde(P, nodes=20, save_field_every=0), ValidationError,
     "save_field_every"),
    ("initial_twist-shape", lambda: ds.solve_pde(P, nodes=20, initial_twist=np.zeros(19)), ValidationError,
     "initial_twist"),
    ("initial_twist-2d", lambda: ds.solve_pde(P, nodes=20, initial_twist=np.zeros((20, 1))), ValidationError,
     "initial_twist"),
    ("initial_twist-nan", lambda: ds.solve_pde(P, nodes=20, initial_twist=np.full(20, NAN)), ValidationError,
     "initial_twist"),
    ("initial_velocity-string", lambda: ds.solve_pde(P, nodes=20, initial_velocity="abc"), ValidationError,
     "initial_velocity"),
    ("initial_velocity-objects", lambda: ds.solve_pde(P, nodes=20, initial_velocity=np.array([None] * 20)),
     ValidationError, "initial_velocity"),
    ("initial_velocity-function-shape", lambda: ds.solve_pde(P, nodes=20, initial_velocity=lambda z: z[:3]),
     ValidationError, "initial_velocity"),
    ("theta-z-outside", lambda: ds.simulate(P, t_end=0.01, samples=3).theta(1e9), ValidationError, "z"),
    ("theta-z-string", lambda: ds.simulate(P, t_end=0.01, samples=3).theta("top"), ValidationError, "z"),
    ("project-modes-zero", lambda: ds.project(P, modes=0), ValidationError, "modes"),
    ("preset-unknown", lambda: ds.preset("copper"), ValidationError, "preset"),
    ("replace-unknown-field", lambda: P.replace(colour="red"), ValidationError, "colour"),
    # integers too large for a float, or for the core's 64-bit integers (OverflowError before)
    ("modes-10**400", lambda: ds.simulate(P, modes=HUGE), ValidationError, "modes"),
    ("project-modes-10**400", lambda: ds.project(P, modes=-HUGE), ValidationError, "modes"),
    ("samples-10**400", lambda: ds.simulate(P, samples=HUGE), ValidationError, "samples"),
    ("samples-2**63", lambda: ds.simulate(P, samples=2**63), ValidationError, "samples"),
    ("pde-samples-10**400", lambda: ds.solve_pde(P, nodes=20, samples=HUGE), ValidationError, "samples"),
    ("t_end-10**400", lambda: ds.simulate(P, t_end=HUGE), ValidationError, "t_end"),
    ("pde-t_end-10**400", lambda: ds.solve_pde(P, nodes=20, t_end=HUGE), ValidationError, "t_end"),
    ("rtol-10**400", lambda: ds.simulate(P, rtol=HUGE), ValidationError, "rtol"),
    ("atol-10**400", lambda: ds.solve_pde(P, nodes=20, atol=-HUGE), ValidationError, "atol"),
    ("dt-10**400", lambda: ds.simulate(P, method="rk4", dt=HUGE), ValidationError, "dt"),
    ("max_steps-10**400", lambda: ds.simulate(P, max_steps=HUGE), ValidationError, "max_steps"),
    ("nodes-10**400", lambda: ds.solve_pde(P, nodes=HUGE), ValidationError, "nodes"),
    ("save_field_every-10**400", lambda: ds.solve_pde(P, nodes=20, save_field_every=HUGE), ValidationError,
     "save_field_every"),
    ("t_eval-10**400", lambda: ds.simulate(P, t_eval=[0.0, HUGE]), ValidationError, "t_eval"),
    ("initial_twist-10**400", lambda: ds.solve_pde(P, nodes=20, initial_twist=[HUGE] * 20), ValidationError,
     "initial_twist"),
    ("linspace-stop-10**400", lambda: expand_axes({"length": ds.linspace(100.0, HUGE, 3)}), ValidationError,
     "grid.length.stop"),
    ("linspace-start-10**400", lambda: expand_axes({"omega": ds.linspace(-HUGE, 1.0, 3)}), ValidationError,
     "grid.omega.start"),
    ("linspace-count-10**400", lambda: expand_axes({"length": ds.linspace(100.0, 200.0, HUGE)}), ValidationError,
     "grid.length.count"),
    ("logspace-stop-10**400", lambda: expand_axes({"length": ds.logspace(1.0, HUGE, 3)}), ValidationError,
     "grid.length.stop"),
    ("linspace-count-float", lambda: expand_axes({"length": ds.linspace(100.0, 200.0, 3.0)}), ValidationError,
     "grid.length.count"),
    ("grid-key-c-400-digits", lambda: expand_axes({"c" + HUGE_TEXT: [0.1]}), ValidationError, "grid"),
    ("grid-key-c257", lambda: expand_axes({"c257": [0.1]}), ValidationError, "grid"),  # no model has mode 257
    ("from_dict-10**400", lambda: ds.Parameters.from_dict({"preset": "steel", "length": HUGE}), ValidationError,
     "length"),
    # methods that advance q'' = a(q) only refuse velocity-dependent (damping) forces
    ("damped-central", lambda: ds.simulate(P.replace(damping_rate=1.0), method="central", t_end=0.01),
     ValidationError, "method"),
    ("damped-verlet", lambda: ds.simulate(P.replace(damping_rate=1.0), method="verlet", t_end=0.01),
     ValidationError, "method"),
    ("pde-damped-verlet", lambda: ds.solve_pde(P.replace(damping_rate=1.0), nodes=20, method="verlet", t_end=0.01),
     ValidationError, "method"),
    ("stability-damping-negative", lambda: ds.studies.stability.analyse(ds.project(P, modes=1), damping_rate=-1.0),
     ValidationError, "damping_rate"),
]


@pytest.mark.parametrize(
    "call, error, field", [c[1:] for c in OPTION_CASES], ids=[c[0] for c in OPTION_CASES]
)
def test_bad_option_is_refused_naming_the_field(call: Callable[[], Any], error: type, field: str) -> None:
    with pytest.raises(error) as info:
        call()
    if isinstance(info.value, ValidationError):
        assert info.value.field == field
    assert field in str(info.value)


def test_a_failing_solve_raises_solve_error_with_the_partial_result() -> None:
    with pytest.raises(SolveError) as info:
        ds.simulate(P, t_end=1.0, max_steps=10)
    assert info.value.status == "max_steps" and "max_steps" in str(info.value)
    assert info.value.result is not None and 0 < info.value.result.t.size < 1001
    assert np.all(np.isfinite(info.value.result.q))


# ------------------------------------------------------------------ resource guards


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: ds.simulate(P, samples=10**9), "samples"),
        (lambda: ds.simulate(P, t_end=1.0, method="rk4", dt=1e-12, max_steps=10**12), "dt"),
        (lambda: ds.solve_pde(P, nodes=10**6), "nodes"),
        (lambda: ds.solve_pde(P, nodes=10**5, samples=10**4), "samples"),
        (lambda: ds.solve_pde(P, nodes=10**5, method="verlet"), "dt"),
    ],
    ids=["samples-1e9", "every-step-1e12", "nodes-1e6", "pde-samples", "pde-every-step"],
)
def test_outputs_beyond_the_memory_budget_are_refused_up_front(call: Callable[[], Any], field: str) -> None:
    with pytest.raises(ValidationError) as info:
        call()
    assert info.value.field == field
    message = str(info.value)
    assert "memory budget of 2 GiB" in message and "would need" in message and "bytes" in message


def test_the_memory_budget_is_configurable(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DRILLSTRING_MEMORY_BUDGET", "100K")
    with pytest.raises(ValidationError) as info:
        ds.simulate(P, samples=2000)  # 2000 samples x (1 + 2 x 6) x 8 bytes = 208 000 bytes
    assert info.value.field == "samples" and "100 KiB" in str(info.value) and "208000 bytes" in str(info.value)
    assert ds.simulate(P, samples=900, t_end=0.01).t.size == 900  # 93 600 bytes fit
    with pytest.raises(ValidationError) as info:
        ds.simulate(P, t_eval=np.linspace(0, 1, 2000))
    assert info.value.field == "t_eval"
    monkeypatch.setenv("DRILLSTRING_MEMORY_BUDGET", "lots")
    with pytest.raises(ValidationError) as info:
        ds.simulate(P, t_end=0.01)
    assert info.value.field == "DRILLSTRING_MEMORY_BUDGET"
    monkeypatch.delenv("DRILLSTRING_MEMORY_BUDGET")
    monkeypatch.setattr(ds.limits, "MEMORY_BUDGET", 10_000)
    with pytest.raises(ValidationError, match="samples"):
        ds.simulate(P, samples=200)


def test_fixed_step_counts_beyond_the_default_limit_are_refused_up_front() -> None:
    with pytest.raises(ValidationError) as info:
        ds.simulate(P, method="rk4", dt=1e-9, t_eval=[0.0, 1.0])  # 10^9 steps > 10^8
    assert info.value.field == "dt"
    assert "1000000000 needed" in str(info.value) and "max_steps" in str(info.value)
    # An explicit max_steps is honoured: the solve runs and stops there.
    res = ds.simulate(P, method="rk4", dt=1e-9, t_eval=[0.0, 1.0], max_steps=100, check=False)
    assert res.status == "max_steps" and res.stats.naccept == 100


# ------------------------------------------------------------------ TOML files


def _toml(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "case.toml"
    path.write_text(text)
    return path


TOML_CASES = [
    ("malformed", '[parameters]\nlength = 100.0\nomega = = 3\n', "toml", 3),
    ("truncated", "[parameters]\nlength = 100.0\ninitial_velocities = [0.1,\n", "toml", None),
    ("truncated-table", "[parameters\nlength = 1.0\n", "toml", 1),
    ("not-utf8", b"[parameters]\nlength = \xff\n", "toml", None),
    ("unknown-key", "[parameters]\nlength = 100.0\n\ncolour = 'red'\n", "colour", 4),
    ("wrong-type", '# a comment\n[parameters]\nlength = "100"\n', "length", 3),
    ("out-of-range", "[parameters]\npreset = 'steel'\npoisson_ratio = 0.5\n", "poisson_ratio", 3),
    ("bad-array-item", "[parameters]\ninitial_velocities = [0.1, 'x']\n", "initial_velocities", 2),
    ("unknown-preset", "[parameters]\npreset = 'copper'\n", "preset", 2),
    ("no-parameters-table", "[solver]\nmodes = 3\n", "parameters", None),
    ("length-400-digits", f"[parameters]\nomega = 1.0\nlength = {HUGE_TEXT}\n", "length", 3),
    ("length-1e400", "[parameters]\nlength = 1e400\n", "length", 2),
    ("velocity-400-digits", f"[parameters]\ninitial_velocities = [0.1, -{HUGE_TEXT}]\n", "initial_velocities", 2),
    ("integer-5000-digits", "[parameters]\nlength = " + "7" * 5000 + "\n", "toml", None),  # int() refuses it
    ("deeply-nested-array", DEEP_TOML, "toml", None),  # RecursionError in the parser before
    ("deeply-nested-inline-table", "[parameters]\na = " + "{b = " * 10_000 + "\n", "toml", None),
]


@pytest.mark.parametrize("text, key, line", [c[1:] for c in TOML_CASES], ids=[c[0] for c in TOML_CASES])
def test_bad_toml_names_file_line_and_key(tmp_path: Path, text: Any, key: str, line: Any) -> None:
    path = tmp_path / "case.toml"
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    with pytest.raises(ValidationError) as info:
        ds.load(path)
    message = str(info.value)
    assert str(path) in message and key in message
    assert info.value.source == str(path) and info.value.field.split("[")[0] == key
    if line is not None:
        assert info.value.line == line and f"line {line}" in message


def _cli(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse usage errors
        code = int(exc.code or 0)
    err = capsys.readouterr().err
    return code, err


SOLVER_TOML_CASES = [
    ("unknown-solver-key", "[parameters]\nlength = 100.0\n[solver]\nmodez = 3\n", "solver.modez", 4),
    ("wrong-typed-solver-value", "[parameters]\n[solver]\nt_end = 1.0\nmodes = '3'\n", "solver.modes", 4),
    ("bad-solver-value", "[parameters]\n[solver]\nmodes = 3\nrtol = -1e-9\n", "rtol", 4),
    ("bad-parameter-value", "[parameters]\nlength = -100.0\n", "length", 2),
    ("malformed", "[solver\n", "toml", 1),
    ("length-400-digits", f"[parameters]\nlength = {HUGE_TEXT}\n", "length", 2),
    ("solver-modes-400-digits", f"[parameters]\n[solver]\nmodes = {HUGE_TEXT}\n", "modes", 3),
    ("solver-samples-400-digits", f"[parameters]\n[solver]\nt_end = 0.01\nsamples = {HUGE_TEXT}\n", "samples", 4),
    ("solver-t_end-400-digits", f"[parameters]\n[solver]\nt_end = {HUGE_TEXT}\n", "t_end", 3),
    ("solver-z-400-digits", f"[parameters]\n[solver]\nt_end = 0.01\nz = {HUGE_TEXT}\n", "z", 4),
]


@pytest.mark.parametrize("text, key, line", [pytest.param(*c[1:], id=c[0]) for c in SOLVER_TOML_CASES])
def test_cli_config_errors_name_file_line_and_key(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str, key: str, line: int
) -> None:
    path = _toml(tmp_path, text)
    code, err = _cli(["simulate", str(path)], capsys)
    assert code == 2
    assert err.count("\n") == 1 and err.startswith(f"drillstring: error: {path}, line {line}: invalid {key}")


# ------------------------------------------------------------------ command line

CLI_CASES = [
    ("modes-zero", ["simulate", "--modes", "0"], "modes"),
    ("t_end-negative", ["simulate", "--t-end", "-1"], "t_end"),
    ("t_end-nan", ["pde", "--nodes", "20", "--t-end", "nan"], "t_end"),
    ("rtol-zero", ["simulate", "--rtol", "0"], "rtol"),
    ("atol-inf", ["pde", "--nodes", "20", "--atol", "inf"], "atol"),
    ("dt-negative", ["simulate", "--method", "rk4", "--dt", "-1e-4"], "dt"),
    ("samples-one", ["simulate", "--samples", "1"], "samples"),
    ("samples-1e9", ["simulate", "--samples", "1000000000"], "samples"),
    ("nodes-two", ["pde", "--nodes", "2"], "nodes"),
    ("length-zero", ["simulate", "--length", "0"], "length"),
    ("omega-inf", ["simulate", "--omega", "inf"], "omega"),
    ("damping_rate-negative", ["simulate", "--damping-rate", "-1"], "damping_rate"),
    ("damping_rate-nan", ["pde", "--nodes", "20", "--damping-rate", "nan"], "damping_rate"),
    ("damped-central", ["simulate", "--damping-rate", "1", "--method", "central", "--t-end", "0.01"], "method"),
    ("velocities-nan", ["simulate", "--initial-velocities", "0.1,nan"], "initial_velocities"),
    ("z-outside", ["simulate", "--t-end", "0.01", "--z", "-1"], "z"),
    ("config-and-preset", ["simulate", "examples/reference.toml", "--preset", "steel"], "--preset"),
    ("missing-config", ["simulate", "no-such-file.toml"], "no-such-file.toml"),
    ("unknown-option", ["simulate", "--frequency", "3"], "--frequency"),
    ("unknown-subcommand", ["frobnicate"], "frobnicate"),
    ("bad-float", ["simulate", "--t-end", "soon"], "--t-end"),
    ("bad-int", ["pde", "--nodes", "many"], "--nodes"),
    ("bad-method", ["simulate", "--method", "euler"], "--method"),
    ("bad-velocities", ["simulate", "--initial-velocities", "a,b"], "--initial-velocities"),
    ("dt-too-small", ["simulate", "--method", "rk4", "--dt", "1e-12"], "dt"),
    ("modes-400-digits", ["simulate", "--modes", HUGE_TEXT], "modes"),
    ("samples-400-digits", ["simulate", "--samples", HUGE_TEXT], "samples"),
    ("nodes-400-digits", ["pde", "--nodes", HUGE_TEXT], "nodes"),
    ("save-field-every-400-digits", ["pde", "--nodes", "20", "--save-field-every", HUGE_TEXT], "save_field_every"),
    ("length-400-digits", ["simulate", "--length", HUGE_TEXT], "length"),  # float("1000...0") is inf
    ("t_end-400-digits", ["simulate", "--t-end", "-" + HUGE_TEXT], "t_end"),
    ("modes-5000-digits", ["simulate", "--modes", "9" * 5000], "--modes"),  # int() refuses it: a usage error
]


@pytest.mark.parametrize("argv, needle", [c[1:] for c in CLI_CASES], ids=[c[0] for c in CLI_CASES])
def test_cli_errors_are_one_line_with_exit_status_2(
    argv: list[str], needle: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code, err = _cli(argv, capsys)
    assert code == 2
    assert err.count("\n") == 1 and "error:" in err and needle in err
    assert "Traceback" not in err


def test_cli_errors_in_a_real_process_have_no_traceback() -> None:
    for argv, needle in (
        (["simulate", "--rtol", "-1"], "rtol"),
        (["pde", "--nodes", "1000000"], "memory budget"),
        (["simulate", "--bogus"], "unrecognized arguments"),
    ):
        proc = subprocess.run(
            [sys.executable, "-m", "drillstring", *argv], capture_output=True, text=True, timeout=120
        )
        assert proc.returncode == 2, proc.stderr
        assert proc.stderr.count("\n") == 1 and needle in proc.stderr and "Traceback" not in proc.stderr


REAL_PROCESS_CASES = [
    ("modes-400-digits", ["simulate", "--modes", HUGE_TEXT], None, "invalid modes"),
    ("samples-400-digits", ["simulate", "--samples", HUGE_TEXT], None, "invalid samples"),
    ("toml-length-400-digits", ["simulate", "{file}"], f"[parameters]\nlength = {HUGE_TEXT}\n",
     "line 2: invalid length"),
    ("toml-deeply-nested", ["pde", "{file}"], DEEP_TOML, "invalid toml"),
    ("sweep-toml-deeply-nested", ["sweep", "{file}", "--out", "{dir}"], DEEP_TOML, "invalid toml"),
]


@pytest.mark.parametrize("argv, text, needle", [c[1:] for c in REAL_PROCESS_CASES],
                         ids=[c[0] for c in REAL_PROCESS_CASES])
def test_numbers_too_large_and_nesting_too_deep_exit_2_without_traceback(
    tmp_path: Path, argv: list[str], text: Any, needle: str
) -> None:
    """Before: OverflowError / RecursionError tracebacks with exit status 1."""
    path = tmp_path / "case.toml"
    if text is not None:
        path.write_text(text)
    args = [a.format(file=path, dir=tmp_path / "out") for a in argv]
    proc = subprocess.run([sys.executable, "-m", "drillstring", *args], capture_output=True, text=True,
                          timeout=120, cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert proc.stderr.startswith("drillstring: error: ") and needle in proc.stderr, proc.stderr
    if text is not None:
        assert str(path) in proc.stderr
    assert len(proc.stderr) < 400  # the 401 digits are not echoed


# ------------------------------------------------------------------ the raw bindings

NO_TERMS = np.zeros((0, 4), dtype=np.int64)
SYSTEM = _core.ModalSystem(np.ones(2), np.ones(2), NO_TERMS, np.zeros(0))
PDE = _core.PdeSystem(1.0, 1.0, 0.1, 0.1, 0.1, 0.0, 1.0, 10)


def _solve(**changes: Any) -> Any:
    args: dict[str, Any] = {
        "system": SYSTEM, "q0": np.zeros(2), "v0": np.ones(2), "t_end": 1.0, "t_eval": None,
        "method": "dop853", "rtol": 1e-9, "atol": 1e-12,
    }
    args.update(changes)
    return _core.solve_modal(**args)


CORE_CASES: list[tuple[str, Callable[[], Any], type, str]] = [
    ("mass-float32", lambda: _core.ModalSystem(np.ones(2, np.float32), np.ones(2), NO_TERMS, np.zeros(0)),
     TypeError, "mass"),
    ("modal-damping-negative", lambda: _core.ModalSystem(np.ones(2), np.ones(2), NO_TERMS, np.zeros(0), -1.0),
     ValidationError, "damping_rate"),
    ("pde-damping-nan", lambda: _core.PdeSystem(1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 5, damping_rate=NAN),
     ValidationError, "damping_rate"),
    ("mass-int", lambda: _core.ModalSystem(np.ones(2, np.int64), np.ones(2), NO_TERMS, np.zeros(0)),
     TypeError, "mass"),
    ("mass-2d", lambda: _core.ModalSystem(np.ones((2, 1)), np.ones(2), NO_TERMS, np.zeros(0)), TypeError, "mass"),
    ("mass-list", lambda: _core.ModalSystem([1.0, 1.0], np.ones(2), NO_TERMS, np.zeros(0)), TypeError, "mass"),
    ("mass-negative", lambda: _core.ModalSystem(-np.ones(2), np.ones(2), NO_TERMS, np.zeros(0)),
     ValidationError, "mass[0]"),
    ("stiffness-length", lambda: _core.ModalSystem(np.ones(2), np.ones(3), NO_TERMS, np.zeros(0)),
     ValidationError, "stiffness"),
    ("stiffness-nan", lambda: _core.ModalSystem(np.ones(2), np.array([1.0, NAN]), NO_TERMS, np.zeros(0)),
     ValidationError, "stiffness[1]"),
    ("quartic_index-float", lambda: _core.ModalSystem(np.ones(2), np.ones(2), np.zeros((1, 4)), np.zeros(1)),
     TypeError, "quartic_index"),
    ("quartic_index-shape", lambda: _core.ModalSystem(np.ones(2), np.ones(2), np.zeros((1, 3), np.int64),
                                                      np.zeros(1)), ValidationError, "quartic_index"),
    ("quartic_index-negative", lambda: _core.ModalSystem(np.ones(2), np.ones(2), -np.ones((1, 4), np.int64),
                                                         np.zeros(1)), ValidationError, "quartic_index[0]"),
    ("quartic_index-out-of-range", lambda: _core.ModalSystem(np.ones(2), np.ones(2), np.full((1, 4), 7, np.int64),
                                                             np.ones(1)), ValidationError, "quartic_index[0]"),
    ("quartic_coef-inf", lambda: _core.ModalSystem(np.ones(2), np.ones(2), np.zeros((1, 4), np.int64),
                                                   np.array([INF])), ValidationError, "quartic_coef[0]"),
    ("q0-length", lambda: _solve(q0=np.zeros(3)), ValidationError, "q0"),
    ("q0-float32", lambda: _solve(q0=np.zeros(2, np.float32)), TypeError, "q0"),
    ("v0-nan", lambda: _solve(v0=np.array([0.0, NAN])), ValidationError, "v0"),
    ("v0-2d", lambda: _solve(v0=np.zeros((2, 1))), TypeError, "v0"),
    ("t_eval-2d", lambda: _solve(t_eval=np.zeros((2, 2))), TypeError, "t_eval"),
    ("t_eval-int", lambda: _solve(t_eval=np.arange(2)), TypeError, "t_eval"),
    ("t_eval-unsorted", lambda: _solve(t_eval=np.array([0.5, 0.1])), ValidationError, "t_eval"),
    ("t_end-nan", lambda: _solve(t_end=NAN), ValidationError, "t_end"),
    ("method-int", lambda: _solve(method=3), TypeError, "method"),
    ("method-unknown", lambda: _solve(method="euler"), ValidationError, "method"),
    ("rtol-string", lambda: _solve(rtol="tight"), TypeError, "rtol"),
    ("rtol-negative", lambda: _solve(rtol=-1.0), ValidationError, "rtol"),
    ("max_steps-negative", lambda: _solve(max_steps=-1), ValidationError, "max_steps"),
    ("max_steps-huge", lambda: _solve(max_steps=2**70), ValidationError, "max_steps"),
    ("max_steps-float", lambda: _solve(max_steps=1.5), ValidationError, "max_steps"),
    ("dt-missing", lambda: _solve(method="rk4"), ValidationError, "dt"),
    ("system-none", lambda: _solve(system=None), TypeError, "system"),
    ("system-pde-for-modal", lambda: _solve(system=PDE), TypeError, "system"),
    ("energy-1d", lambda: SYSTEM.energy(np.zeros(2), np.zeros(2)), TypeError, "q"),
    ("energy-shape", lambda: SYSTEM.energy(np.zeros((3, 4)), np.zeros((3, 4))), ValidationError, "q"),
    ("acceleration-length", lambda: SYSTEM.acceleration(np.zeros(5)), ValidationError, "q"),
    ("pde-nodes-negative", lambda: _core.PdeSystem(1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1), ValidationError,
     "nodes"),
    ("pde-nodes-huge", lambda: _core.PdeSystem(1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2**70), ValidationError,
     "nodes"),
    ("pde-nodes-float", lambda: _core.PdeSystem(1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 10.5), ValidationError,
     "nodes"),
    ("pde-k1-nan", lambda: _core.PdeSystem(NAN, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 10), ValidationError, "k1"),
    ("pde-length-zero", lambda: _core.PdeSystem(1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 10), ValidationError,
     "length"),
    ("pde-count-zero", lambda: PDE.linear_frequencies_squared(0), ValidationError, "count"),
    ("pde-count-negative", lambda: PDE.linear_frequencies_squared(-3), ValidationError, "count"),
    ("pde-q0-length", lambda: _core.solve_pde(PDE, np.zeros(3), np.zeros(10), 1.0, None, "dop853", 1e-9, 1e-12),
     ValidationError, "q0"),
    ("pde-v0-int", lambda: _core.solve_pde(PDE, np.zeros(10), np.zeros(10, np.int32), 1.0, None, "dop853",
                                           1e-9, 1e-12), TypeError, "v0"),
]


@pytest.mark.parametrize("call, error, field", [c[1:] for c in CORE_CASES], ids=[c[0] for c in CORE_CASES])
def test_raw_bindings_raise_type_or_value_errors(call: Callable[[], Any], error: type, field: str) -> None:
    with pytest.raises(error) as info:
        call()
    assert isinstance(info.value, (TypeError, ValueError))
    if isinstance(info.value, ValidationError):
        assert info.value.field == field
    assert field in _message(info.value)


def test_the_case_table_is_large() -> None:
    total = (len(PARAMETER_CASES) + len(OPTION_CASES) + len(TOML_CASES) + len(SOLVER_TOML_CASES)
             + len(CLI_CASES) + len(CORE_CASES) + len(REAL_PROCESS_CASES))
    assert total >= 40
    names = [c[0] for c in OPTION_CASES] + [c[0] for c in CORE_CASES] + [c[0] for c in CLI_CASES]
    assert len(set(names)) >= 40


def test_numbers_in_solver_messages_have_at_most_ten_significant_digits() -> None:
    # Before: the core printed every float in full ("t = 0.0006103515625000001" and, for tiny
    # steps, hundreds of digits); now as Python's ".10g" would, e.g. "t = 2.5e-05".
    import re

    messages = [
        ds.simulate(ds.preset("aluminum"), t_end=1.0, max_steps=7, check=False).message,
        ds.simulate(ds.preset("aluminum"), t_end=1.0 / 3.0, method="rk4", dt=1e-5, max_steps=3, check=False).message,
        ds.solve_pde(ds.preset("aluminum"), nodes=20, t_end=0.1, max_steps=5, check=False).message,
    ]
    for message in messages:
        numbers = re.findall(r"\d[\d.]*(?:e[+-]\d+)?", message)
        assert numbers and "t = " in message, message
        for number in numbers:
            digits = re.sub(r"e[+-]\d+$", "", number).replace(".", "").lstrip("0")
            assert len(digits) <= 10, (number, message)
    # the grid's step is t_end / ceil(t_end / dt): 3 steps end at 2.999940001e-05
    assert "t = 2.999940001e-05 before t_end = 0.3333333333:" in messages[1], messages[1]
