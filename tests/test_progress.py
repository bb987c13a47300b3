"""Progress reports of single solves, sweeps and the command line (tqdm)."""

import io
import sys

import numpy as np
import pytest

import drillstring as ds
from drillstring.cli import main

ALUMINUM = ds.preset("aluminum")


def test_callable_gets_start_and_end_and_results_are_unchanged():
    calls = []
    plain = ds.simulate(ALUMINUM, modes=3, t_end=0.2, samples=21)
    watched = ds.simulate(ALUMINUM, modes=3, t_end=0.2, samples=21, progress=lambda t, end: calls.append((t, end)))
    assert calls[0] == (0.0, 0.2) and calls[-1] == (0.2, 0.2)
    assert [t for t, _ in calls] == sorted(t for t, _ in calls)
    assert np.array_equal(plain.q, watched.q) and plain.stats == watched.stats


def test_pde_bar_on_stderr_reaches_t_end(capsys):
    plain = ds.solve_pde(ALUMINUM, nodes=30, t_end=0.05, samples=11)
    shown = ds.solve_pde(ALUMINUM, nodes=30, t_end=0.05, samples=11, progress=True)
    err = capsys.readouterr().err
    assert "solve_pde: 100%" in err and "t = 0.05/0.05 s" in err
    assert np.array_equal(plain.q, shown.q)
    ds.solve_pde(ALUMINUM, nodes=30, t_end=0.05, samples=11)
    assert capsys.readouterr().err == ""  # off by default


def test_a_bar_leaves_no_thread_behind():
    # tqdm's monitor thread would outlive the bar; a command forks its figure processes after a
    # solve with a bar only while no other thread runs (drillstring.io.figures.FigureJobs)
    import subprocess

    code = ("import sys, threading, drillstring as ds\n"
            "ds.simulate(ds.preset('aluminum'), modes=3, t_end=0.05, samples=11, progress=True)\n"
            "from tqdm import tqdm\n"
            "print(threading.active_count(), tqdm.monitor_interval)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "simulate: 100%" in done.stderr
    assert done.stdout.split() == ["1", "10"]  # no thread left, tqdm's own setting kept


def test_a_stopped_solve_reports_where_it_stopped():
    calls = []
    res = ds.simulate(ALUMINUM, t_end=1.0, max_steps=20, check=False, progress=lambda t, end: calls.append(t))
    assert res.status == "max_steps"
    assert calls[-1] == pytest.approx(float(res.t[-1])) and 0 < calls[-1] < 1.0


@pytest.mark.parametrize("bad", ["yes", 1, None])
def test_bad_progress_names_the_option(bad):
    with pytest.raises(ds.ValidationError, match="progress.*True, False or a callable"):
        ds.simulate(ALUMINUM, t_end=0.01, progress=bad)
    with pytest.raises(ds.ValidationError, match="progress"):
        ds.solve_pde(ALUMINUM, nodes=10, t_end=0.01, progress=bad)


def test_the_core_reports_the_time_reached_while_it_steps():
    # a solve of a few hundred ms: the core reports every ~20 ms, times rise, results unchanged
    for solve in (lambda **kw: ds.simulate(ALUMINUM, modes=8, rigid_mode=True, t_end=20.0, samples=101, **kw),
                  lambda **kw: ds.solve_pde(ALUMINUM, nodes=400, t_end=3.0, samples=11, **kw)):
        calls: list = []
        watched = solve(progress=lambda t, end, calls=calls: calls.append(t))
        plain = solve()
        inside = [t for t in calls if 0.0 < t < calls[-1]]
        assert len(inside) >= 3, calls
        assert calls == sorted(calls) and calls[0] == 0.0
        assert np.array_equal(plain.q, watched.q) and plain.stats == watched.stats


def test_an_exception_of_the_callable_stops_the_solve():
    def stop(t, end):
        if t > 0.0:
            raise RuntimeError(f"stop at {t}")

    with pytest.raises(RuntimeError, match="stop at"):
        ds.simulate(ALUMINUM, modes=8, rigid_mode=True, t_end=1e4, samples=11, progress=stop)


def test_sweep_bar_counts_runs(capsys):
    ds.sweep(ALUMINUM, {"length": [100.0, 120.0, 140.0]}, chunk_size=1, progress=True, modes=1, t_end=0.01)
    err = capsys.readouterr().err
    assert "sweep:" in err and "1/3 runs" in err and "3/3 runs" in err and "runs/s" in err


@pytest.mark.parametrize("command", [["simulate", "--preset", "aluminum", "--modes", "1"],
                                     ["pde", "--preset", "aluminum", "--nodes", "20"]])
def test_command_line_progress_flag(command, capsys):
    assert main([*command, "--t-end", "0.01", "--progress"]) == 0
    assert "100%" in capsys.readouterr().err
    assert main([*command, "--t-end", "0.01", "--no-progress"]) == 0
    assert capsys.readouterr().err == ""
    assert main([*command, "--t-end", "0.01"]) == 0  # stderr is not a terminal here
    assert capsys.readouterr().err == ""


def test_convergence_progress_lines(capsys):
    from drillstring.studies import convergence

    convergence.study(ALUMINUM, t_end=0.01, samples=11, modes=(1,), cells=8, max_nodes=33, progress=True)
    lines = capsys.readouterr().err.splitlines()
    assert lines[0].startswith("PDE N =     9:") and lines[-1].startswith("Galerkin  1 modes: error")
    convergence.study(ALUMINUM, t_end=0.01, samples=11, modes=(1,), cells=8, max_nodes=33)
    assert capsys.readouterr().err == ""


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_on_a_terminal_commands_show_bars_by_default(monkeypatch):
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    assert main(["simulate", "--preset", "aluminum", "--modes", "1", "--t-end", "0.01"]) == 0
    assert "simulate: 100%" in terminal.getvalue() and "t = 0.01/0.01 s" in terminal.getvalue()


def test_convergence_bar_on_a_terminal_counts_solves(monkeypatch):
    from drillstring.studies import convergence

    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    convergence.study(ALUMINUM, t_end=0.01, samples=11, modes=(1, 2), cells=8, max_nodes=33, progress=True)
    text = terminal.getvalue()
    # 3 grid levels and 2 Galerkin sizes; each line is written above the bar
    assert "convergence: 100%" in text and "5/5" in text
    assert "PDE N =    33:" in text and "Galerkin  2 modes: error" in text
