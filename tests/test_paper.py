"""``drillstring paper``: the whole reproduction, end to end, in its quick form."""

from __future__ import annotations

import contextlib
import csv
import errno
import io
import os
import re
import shutil

import numpy as np
import pytest

import drillstring as ds
from drillstring import report as paper
from drillstring.cli import main
from drillstring.io import output as io_output

SCALE = paper.QUICK_T_END_SCALE  # 0.1: the 1-s runs last 0.1 s, the 10-s runs 1 s
SPS = paper.QUICK_SAMPLES_PER_SECOND
KW = dict(rtol=1e-10, atol=1e-13)


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("paper")
    stdout, stderr = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        code = main(["paper", "--out", str(out), "--quick"])
    return out, code, stdout.getvalue(), stderr.getvalue()


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    return rows[0], rows[1:]


def columns(path):
    header, rows = read_csv(path)
    data = np.array(rows, dtype=float)
    return {name: data[:, k] for k, name in enumerate(header)}


def test_command_succeeds_quietly_off_a_terminal(quick):
    out, code, stdout, stderr = quick
    assert code == 0
    assert stderr == ""  # progress lines only on a terminal
    assert f"wrote 38 files to {out}" in stdout
    assert re.search(r"figure claims: \d+ supported, \d+ partly, \d+ contradicted", stdout)


def test_every_file_appears(quick):
    out = quick[0]
    names = [f"fig{n:02d}.{ext}" for n in range(1, 16) for ext in ("png", "csv")]
    names += ["table2.csv", "stability.csv", "report.md", "report.html"]
    names += ["convergence.csv", "grids.csv", "reference.csv", "convergence.png"]
    assert sorted(p.name for p in out.iterdir()) == sorted(names)
    for name in names:
        assert (out / name).stat().st_size > 0, name
    for n in range(1, 16):
        png = (out / f"fig{n:02d}.png").read_bytes()
        assert png[:8] == b"\x89PNG\r\n\x1a\n"
        assert png.__len__() > 20_000  # a real figure, not an empty canvas


EXPECTED_HEADERS = {
    1: ["t", "theta1", "theta1_dot"],
    2: ["t", "theta1", "theta1_dot"],
    3: ["t", "theta1_linear", "theta1_dot_linear", "theta1_nonlinear", "theta1_dot_nonlinear", "phase_shift_deg"],
    4: ["t", "theta1_linear", "theta1_dot_linear", "theta1_nonlinear", "theta1_dot_nonlinear"],
    5: ["t", "theta1_linear", "theta1_dot_linear", "theta1_nonlinear", "theta1_dot_nonlinear", "phase_shift_deg"],
    6: ["t", "theta_zk", "theta_dot_zk", "q1", "q2"],
    8: ["t", "theta_zk", "theta_dot_zk", "q1", "q2", "q3"],
    10: ["t"] + [f"{q}_{tag}" for tag in ("l100", "l250", "l500") for q in ("theta_zk", "theta_dot_zk")],
    12: ["t"] + [f"{q}_{tag}" for tag in ("omega_2pi0.5", "omega_2pi6") for q in ("theta_zk", "theta_dot_zk")],
    14: ["t"] + [f"{q}_{tag}" for tag in ("aluminium", "steel") for q in ("theta_zk", "theta_dot_zk")],
}


@pytest.mark.parametrize("number", sorted(EXPECTED_HEADERS))
def test_figure_csv_columns(quick, number):
    header, rows = read_csv(quick[0] / f"fig{number:02d}.csv")
    assert header == EXPECTED_HEADERS[number]
    data = np.array(rows, dtype=float)
    assert np.all(np.isfinite(data))
    window = (9 * SCALE, 10 * SCALE) if number == 5 else (0.0, SCALE)
    assert data[0, 0] == pytest.approx(window[0]) and data[-1, 0] == pytest.approx(window[1])
    assert data.shape[0] == round((window[1] - window[0]) * SPS) + 1


def close(actual, expected):
    np.testing.assert_allclose(actual, expected, rtol=1e-10, atol=1e-10 * np.max(np.abs(expected)))


def test_figure_data_equal_direct_simulate(quick):
    out = quick[0]
    al = ds.preset("aluminum")
    # Fig. 1: one mode, theta_1
    fig1 = columns(out / "fig01.csv")
    one = ds.simulate(al, modes=1, t_end=SCALE, samples=round(SPS * SCALE) + 1, **KW)
    close(fig1["t"], one.t)
    close(fig1["theta1"], one.q[0])
    close(fig1["theta1_dot"], one.qdot[0])
    # Fig. 5: linear and nonlinear over the last tenth of the long run
    fig5 = columns(out / "fig05.csv")
    n10 = round(SPS * 10 * SCALE) + 1
    lin = ds.simulate(al, modes=1, t_end=10 * SCALE, samples=n10, nonlinear=False, **KW)
    nl = ds.simulate(al, modes=1, t_end=10 * SCALE, samples=n10, **KW)
    tail = slice(n10 - fig5["t"].size, n10)
    close(fig5["theta1_linear"], lin.q[0][tail])
    close(fig5["theta1_nonlinear"], nl.q[0][tail])
    assert fig5["phase_shift_deg"][-1] == pytest.approx(
        np.degrees(ds.studies.analysis.phase_shift(nl.t, lin.q[0], nl.q[0], 10 * SCALE)), rel=1e-9)
    # Fig. 10: l = 500 m, theta and theta_dot at z_k = 2l/3
    fig10 = columns(out / "fig10.csv")
    l500 = ds.simulate(al.replace(length=500.0), modes=3, t_end=SCALE, samples=round(SPS * SCALE) + 1, **KW)
    close(fig10["theta_zk_l500"], l500.theta(1000.0 / 3))
    close(fig10["theta_dot_zk_l500"], l500.theta_dot(1000.0 / 3))
    # Fig. 13: Omega = 2 pi 6; Fig. 15: steel
    fig13 = columns(out / "fig13.csv")
    fast = ds.simulate(al.replace(omega=2 * np.pi * 6), modes=3, t_end=SCALE, samples=round(SPS * SCALE) + 1, **KW)
    close(fig13["theta_zk_omega_2pi6"], fast.theta(200.0 / 3))
    fig15 = columns(out / "fig15.csv")
    steel = ds.simulate(ds.preset("steel"), modes=3, t_end=SCALE, samples=round(SPS * SCALE) + 1, **KW)
    close(fig15["theta_dot_zk_steel"], steel.theta_dot(200.0 / 3))
    # Fig. 7: two modes, with the modal coordinates
    fig7 = columns(out / "fig07.csv")
    two = ds.simulate(al, modes=2, t_end=SCALE, samples=round(SPS * SCALE) + 1, **KW)
    close(fig7["q2"], two.q[1])
    close(fig7["theta_zk"], two.theta(200.0 / 3))


def test_table2_csv(quick):
    header, rows = read_csv(quick[0] / "table2.csv")
    assert header == ["method", "dt", "max_amplitude", "difference_percent"]
    assert len(rows) == 5
    assert rows[0][0] == "Runge-Kutta" and f"{float(rows[0][2]):.3e}" == "5.061e-04"
    assert [float(r[1]) for r in rows[1:]] == [1e-3, 5e-4, 2.5e-4, 1e-4]


def test_stability_csv(quick):
    header, rows = read_csv(quick[0] / "stability.csv")
    assert header == list(paper.STABILITY_COLUMNS)
    assert len(rows) == 5 * (1 + 2 + 3)  # five parameter sets, 1, 2 and 3 modes
    col = {name: k for k, name in enumerate(header)}
    assert {r[col["classification"]] for r in rows} == {"centre"}
    for r in rows:
        assert float(r[col["eigenvalue_real"]]) == 0.0 and float(r[col["eigenvalue_imag"]]) > 0
        params = ds.preset(r[col["material"]].replace("aluminium", "aluminum")).replace(
            length=float(r[col["length_m"]]), omega=float(r[col["omega_rad_s"]]))
        crit = ds.PDECoefficients.from_parameters(params).critical_speed(int(r[col["mode"]]))
        assert float(r[col["critical_speed_rad_s"]]) == pytest.approx(crit, rel=1e-12)
        assert float(r[col["omega_over_critical"]]) < 1
    lengths = {float(r[col["length_m"]]) for r in rows}
    assert lengths == {100.0, 250.0, 500.0}


def test_report_html_is_self_contained(quick):
    text = (quick[0] / "report.html").read_text(encoding="utf-8")
    assert text.count('src="data:image/png;base64,') == 16  # 15 figures and the truncation study
    assert "http://" not in text and "https://" not in text
    assert "<link" not in text and "<script" not in text
    # one per figure with its own curves (a phase portrait refers to its response's table), Table 2,
    # stability, the truncation study, the physics notes, timings
    assert text.count("<table>") == 8 + 5
    assert "<em>Modeling of Drill String Torsional Vibrations" in text


def test_report_md_states_claims_numbers_errata_and_commands(quick):
    text = (quick[0] / "report.md").read_text(encoding="utf-8")
    for n in range(1, 16):
        assert f"## Fig. {n}:" in text
        assert f"](fig{n:02d}.png)" in text and f"(fig{n:02d}.csv)" in text
    assert text.count("**Paper:**") == 17  # 15 figures, Table 2, stability
    assert text.count("**Here (") == 17
    assert "Quick run" in text  # says the numbers are not the paper's
    assert "## Errata" in text and text.count("\n1. Eq. 9") == 1 and "\n5. Table 2" in text
    assert "ds.simulate(ds.preset(\"aluminum\").replace(length=500.0), modes=3, t_end=0.1" in text
    assert "drillstring paper --out" in text and "--quick" in text
    assert "accumulated phase shift" in text
    assert "0.1195 %" in text  # Table 2's rounding-boundary row is reported as such


def test_progress_lines_and_report_object(tmp_path, monkeypatch):
    monkeypatch.setattr(paper.specs, "FIGURES", paper.FIGURES[:2])
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        rep = paper.reproduce(tmp_path, t_end_scale=0.3, samples_per_second=SPS, progress=True)
    lines = err.getvalue().splitlines()
    assert re.fullmatch(r"\[ 1/2\] fig01 one-mode response \.\.\. \d+\.\d s", lines[1])
    assert re.fullmatch(r"\[ 2/2\] fig02 one-mode phase portrait \.\.\. \d+\.\d s", lines[2])
    assert [f.number for f in rep.figures] == [1, 2]
    curve = rep.figures[0].curves[0]
    assert curve.amplitude == pytest.approx(5.06e-4, rel=0.01) and curve.bounded
    assert curve.frequencies[0] == pytest.approx(31.616, rel=2e-3)  # ~9.5 cycles
    assert rep.report_html.exists() and rep.total_seconds > 0


def test_bad_options_are_one_line_errors(tmp_path, capsys):
    assert main(["paper", "--out", str(tmp_path / "x"), "--t-end-scale", "0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "t_end_scale" in err


def test_a_full_disk_mid_write_keeps_the_earlier_reproduction_whole(quick, tmp_path, capsys, monkeypatch):
    out = tmp_path / "paper"
    shutil.copytree(quick[0], out)
    (out / "notes.txt").write_text("mine\n")
    old = {p.name: p.read_bytes() for p in out.iterdir()}
    delivered = []
    real = io_output._deliver

    def deliver(tmp, target):
        if len(delivered) == 3:
            raise OSError(errno.ENOSPC, "No space left on device")
        real(tmp, target)
        delivered.append(os.path.basename(target.real))

    monkeypatch.setattr(io_output, "_deliver", deliver)
    assert main(["paper", "--out", str(out), "--quick"]) == 2
    err = capsys.readouterr().err
    assert delivered == ["fig01.png", "fig01.csv", "fig02.png"]
    assert err.count("\n") == 1 and f"cannot write {out / 'fig02.csv'}: No space left on device" in err
    assert {p.name: p.read_bytes() for p in out.iterdir()} == old  # the earlier report with its own figures
    assert sorted(p.name for p in tmp_path.iterdir()) == ["paper"]


def test_a_folder_another_run_writes_is_refused_before_any_run(tmp_path, capsys, monkeypatch):
    def called(*args, **kwargs):
        raise AssertionError("a run before the folder was taken")

    monkeypatch.setattr(paper.run, "references", called)
    held = io_output.lock_directory(tmp_path, field="x", busy="{holder}")
    try:
        assert main(["paper", "--out", str(tmp_path), "--quick"]) == 2
    finally:
        held.close()
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and str(tmp_path) in err and f"locked by process {os.getpid()}" in err


def test_single_figure_is_a_reusable_matplotlib_figure():
    from matplotlib.figure import Figure

    fig = paper.figure(10, t_end_scale=0.05)
    assert isinstance(fig, Figure)
    assert [line.get_label() for line in fig.axes[0].get_lines()] == ["l = 100 m", "l = 250 m", "l = 500 m"]
    assert fig.axes[0].get_ylabel() == r"$\theta(z_k, t)$, rad"
    assert "different drill string lengths" in fig._suptitle.get_text().replace("\n", " ")
    with pytest.raises(ds.ValidationError):
        paper.figure(16)


def test_report_has_the_truncation_study(quick):
    out = quick[0]
    text = (out / "report.md").read_text(encoding="utf-8")
    assert "Beyond the paper" in text and "convergence.png" in text
    header, rows = read_csv(out / "convergence.csv")
    assert header == ["modes", "rigid_mode", "relative_error", "seconds"]
    errors = {(int(r[0]), r[1] == "True"): float(r[2]) for r in rows}
    # the rigid mode matters once an even mode moves: 3 modes with it beat 3 modes without it
    assert errors[3, True] < errors[3, False]


def _prose(text):
    """The report without code blocks and inline code."""
    return re.sub(r"`[^`]*`", "", re.sub(r"```.*?```", "", text, flags=re.S))


def test_every_verdict_states_its_criterion_and_quick_verdicts_are_indicative(quick):
    text = (quick[0] / "report.md").read_text(encoding="utf-8")
    verdicts = re.findall(r"\*\*Here \(([^)]*)\):\*\* criterion: (\w[^\n]*)", text)
    assert len(verdicts) == 17  # 15 figures, Table 2, stability
    assert sum(v.endswith(", indicative: quick run") for v, _ in verdicts) == 15
    for number, criterion in paper.CRITERIA.items():
        assert f"criterion: {criterion}" in text, number
    assert "verdicts are indicative only" in text and "Fig. 14's does" in text


def test_shared_runs_are_reported_once(quick):
    text = (quick[0] / "report.md").read_text(encoding="utf-8")
    bullets = [line for line in text.splitlines() if line.startswith("- ") and not line.startswith("- As Fig.")]
    assert len(bullets) == len(set(bullets))  # no finding repeated verbatim (references to them aside)
    for key in paper.RUNS:
        if key != "two_mode_linear":  # a reference run, not behind a figure's curves
            assert text.count(f"\n{key} = ds.simulate(") == 1, key
    assert "- As Fig. 1 above (same runs): Amplitude max |θ_1|" in text
    assert "Curves: the table of Fig. 14 (same runs and window)." in text
    assert "# three_mode: as Fig. 8\n# steel: as Fig. 14\n" in text


def test_report_prose_spells_aluminium(quick):
    prose = _prose((quick[0] / "report.md").read_text(encoding="utf-8"))
    assert "aluminum" not in prose and "aluminium" in prose
    assert not [spec.number for spec in paper.FIGURES if "aluminum" in spec.caption + spec.claim]  # PNG titles
    assert ds.preset("aluminium") == ds.preset("aluminum")


def test_no_truncation_error_is_reported_below_the_reference_accuracy(quick):
    text = (quick[0] / "report.md").read_text(encoding="utf-8")
    section = text.split("## Beyond the paper")[1].split("\n## ")[0]
    accuracy = float(re.search(r"the reference itself is accurate to (\S+) ", section).group(1))
    cells = [row.split(" | ")[1:3] for row in section.splitlines() if re.match(r"\| \d+ \|", row)]
    assert len(cells) == 4
    _, rows = read_csv(quick[0] / "convergence.csv")
    for cell in (c.strip(" |") for pair in cells for c in pair):
        if cell.startswith("<"):
            assert cell == f"< {accuracy:.1e} (reference accuracy)"
        else:
            assert float(cell) >= accuracy
    below = [float(r[2]) for r in rows if float(r[2]) < accuracy]
    assert section.count("(reference accuracy)") == len(below)


def _covered(fig, ax):
    """Points of the axes' data lines (densified along each segment) inside its legend box."""
    fig.canvas.draw()
    legend = ax.get_legend()
    if legend is None:
        return 0
    box = legend.get_window_extent()
    count = 0
    for line in ax.get_lines():
        xy = ax.transData.transform(np.column_stack(line.get_data()).astype(float))
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        for a, b in zip(xy[:-1], xy[1:]):
            pts = a + np.linspace(0.0, 1.0, 40)[:, None] * (b - a)
            count += int(np.sum(box.contains_points(pts) if hasattr(box, "contains_points") else
                                [box.contains(*p) for p in pts]))
    return count


def test_convergence_legends_cover_no_curve():
    from drillstring.studies import convergence

    params = ds.preset("aluminum")
    t = np.linspace(0.0, 1.0, 1001)
    reference = 3e-4 * np.sin(2 * np.pi * 31.65 * t)
    grids = [convergence.GridLevel(121, 0.1, None, None, 1e-14), convergence.GridLevel(241, 0.2, 2.2e-2, None, 1e-14),
             convergence.GridLevel(481, 0.5, 5.5e-3, 8.9e-4, 1e-14),
             convergence.GridLevel(961, 1.5, 1.4e-3, 6.5e-5, 1e-14)]
    errors = {1: (0.42, 0.42), 2: (0.28, 0.16), 3: (0.16, 1.9e-2), 4: (0.16, 1.2e-2), 6: (0.17, 9.0e-4),
              8: (0.17, 1.9e-4), 12: (0.17, 4.5e-6), 16: (0.17, 4.4e-6)}  # the README's study
    models = [convergence.ModelError(n, rigid, pair[rigid], 0.01) for n, pair in errors.items() for rigid in (0, 1)]
    curves = {"3 modes": 1.1 * reference, "3 modes + rigid": reference}
    study = convergence.ConvergenceStudy(params, 200 / 3, t, reference, True, 1e-4, grids, models, curves)
    assert study.accuracy == 6.5e-5 and study.shown_error(4.5e-6) == "< 6.5e-05 (reference accuracy)"
    assert study.shown_error(1.9e-4) == "1.9e-04"
    fig = convergence.figure(study)
    assert [_covered(fig, ax) for ax in fig.axes] == [0, 0, 0]
    labels = fig.axes[0].get_legend().get_texts()
    assert "below the reference\naccuracy 6.5e-05" in [text.get_text() for text in labels]


def test_sweep_maps_label_each_critical_speed():
    import pandas as pd

    from drillstring import plots

    base = ds.preset("aluminum")
    rows = [dict(base.to_dict(), length=l, omega=w, max_theta=1e-3 + l * w * 1e-9, share_mode_1=0.5,
                 share_mode_2=0.3, share_mode_3=0.2)
            for l in np.linspace(100.0, 500.0, 9) for w in np.linspace(0.0, 250.0, 9)]
    table = pd.DataFrame(rows)
    fig = plots.sweep_metric(table, "max_theta", axes=["length", "omega"])
    labels = sorted(text.get_text() for text in fig.axes[0].texts)
    assert labels == [r"$\Omega_{crit,1}$", r"$\Omega_{crit,2}$", r"$\Omega_{crit,3}$"]
    # each label sits on its curve at the right edge: Omega_crit,i(l) = i * 37.2 rad/s at l = 525 m
    right = fig.axes[0].get_xlim()[1]
    crit = ds.model.coefficients.PDECoefficients.from_parameters(base.replace(length=right)).critical_speed([1, 2, 3])
    positions = sorted(text.xy for text in fig.axes[0].texts)
    assert [x for x, _ in positions] == pytest.approx([right] * 3, rel=1e-6) and right == 525.0
    assert sorted(y for _, y in positions) == pytest.approx(list(crit), rel=1e-2)


def test_report_has_physics_notes_with_the_functions_numbers(quick):
    text = (quick[0] / "report.md").read_text(encoding="utf-8")
    section = text.split("## Physics notes")[1].split("\n## ")[0]
    assert "Khajiyeva, M.M. Jantassova, A.K. Kudaibergenov" in section
    assert "*Modeling of Drill String Torsional Vibrations Taking into Account Finite Deformations*" in section
    al, steel = ds.preset("aluminum"), ds.preset("steel")

    def coef(p, model):
        return ds.PDECoefficients.from_parameters(p.replace(model=model))

    notes = paper.physics_notes()
    for model in ("paper", "consistent"):
        assert notes.wave_speed_aluminium[model] == coef(al, model).wave_speed
        assert notes.wave_speed_steel[model] == coef(steel, model).wave_speed
        hz = np.asarray(coef(al.replace(omega=0.0), model).linear_frequencies([1, 2, 3])) / (2 * np.pi)
        assert notes.frequencies_hz[model] == tuple(hz)
    # the paper model's shear energy is four times the classical one: twice the wave speed, exactly
    assert notes.wave_speed_aluminium["paper"] / notes.wave_speed_aluminium["consistent"] == 2.0
    assert notes.wave_speed_steel["paper"] / notes.wave_speed_steel["consistent"] == 2.0
    assert notes.frequencies_hz["paper"] == pytest.approx(tuple(2 * f for f in notes.frequencies_hz["consistent"]),
                                                          rel=1e-14)
    crit_al = coef(al, "paper").critical_speed(1)
    crit_st = coef(steel.replace(length=2000.0), "paper").critical_speed(1)
    assert notes.critical_speed_aluminium == {"paper": crit_al, "consistent": np.inf}
    assert notes.critical_speed_steel_2000 == {"paper": crit_st, "consistent": np.inf}
    # the table shows those numbers (the consistent model has no critical speed)
    c_al, c_st = notes.wave_speed_aluminium, notes.wave_speed_steel
    f = notes.frequencies_hz
    assert (f"| wave speed √(k2/k1), aluminium / steel | {c_al['paper']:.0f} / {c_st['paper']:.0f} m/s | "
            f"{c_al['consistent']:.0f} / {c_st['consistent']:.0f} m/s |") in section
    shown = [", ".join(f"{x:.2f}" for x in f[m]) + " Hz" for m in ("paper", "consistent")]
    assert f"| free-free f1, f2, f3, 100 m aluminium (Ω = 0) | {shown[0]} | {shown[1]} |" in section
    assert f"| Ω_crit,1, 100 m aluminium (Table 1) | {crit_al:.1f} rad/s | none |" in section
    assert f"| Ω_crit,1, 2000 m steel (Table 3 geometry) | {crit_st:.2f} rad/s | none |" in section
    assert "(6221 m/s for the aluminium, 2x the classical 3110 m/s)" in section  # the README's values
    assert "| 195.4 rad/s |" in section and "| 10.19 rad/s |" in section


def test_every_figure_has_one_checker_stating_its_criterion():
    numbers = [n for check in paper.checks.CHECKS for n in check.criteria]
    assert sorted(numbers) == [spec.number for spec in paper.FIGURES]  # each figure checked exactly once
    for check in paper.checks.CHECKS:
        assert check.assess.__doc__  # what the checker decides, in words
        for criterion in check.criteria.values():
            assert criterion.startswith("supported if every curve is bounded")


def test_markdown_and_html_rendering_of_the_blocks():
    from drillstring.report import document as d
    from drillstring.report import render

    doc = [d.h1("Title <x>"), d.p("See `a|b` and **bold**, *it* [f](f.csv)."), d.ul(["one", "two"]),
           d.ol(["first"]), d.img("f.png", "a figure"), d.code("x = 1 < 2"), d.table(["h|1", "h2"], [[1, "a|b"]])]
    md = render.markdown(doc)
    assert md == ("# Title <x>\n\nSee `a|b` and **bold**, *it* [f](f.csv).\n\n- one\n- two\n\n1. first\n\n"
                  "![a figure](f.png)\n\n```\nx = 1 < 2\n```\n\n| h\\|1 | h2 |\n|---|---|\n| 1 | a\\|b |\n")
    page = render.html(doc, {"f.png": b"PNG"})
    assert "<title>Title &lt;x&gt;</title>" in page and "<h1>Title &lt;x&gt;</h1>" in page
    assert ("<p>See <code>a|b</code> and <strong>bold</strong>, <em>it</em> <a href=\"f.csv\">f</a>.</p>"
            in page)
    assert "<ul><li>one</li><li>two</li></ul>" in page and "<ol><li>first</li></ol>" in page
    assert '<img src="data:image/png;base64,UE5H" alt="a figure">' in page
    assert "<pre><code>x = 1 &lt; 2</code></pre>" in page
    assert "<th>h|1</th>" in page and "<td>a|b</td>" in page
