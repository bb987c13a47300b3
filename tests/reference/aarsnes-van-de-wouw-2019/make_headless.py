# ruff: noqa: E501  (the inserted Octave lines keep their length)
"""Prepare Aarsnes & van de Wouw's dimensional coupled case (folder ``Coupled``) to run headless in Octave.

    python3 make_headless.py WORKDIR RPM ROP_M_PER_H [--t1 SECONDS] [norecord]
    python3 make_headless.py --stability WORKDIR

WORKDIR holds ``MAIN.m``, ``parameters.m`` and ``waveStep_transportBRI.m`` exported from the published
commit. This script rewrites them in place; no numerical line of theirs is changed:

* ``parameters.m``: the two set-points, ``p.omega0 = 30/60*2*pi;`` and ``p.V0 = 30/3600;``, get RPM and
  ROP instead of 30 (each replaced exactly once; 30 and 30 leave the file unchanged). Everything that
  depends on them (dNom, tN, R, Ka, Kt, omegaMAX, Pl) is computed by their file as before.
* ``waveStep_transportBRI.m``: read-only recording lines are inserted (marked ``% [record]``): before the
  sub-step loop a global counter and an accumulator; at the top of each sub-step's upwind update (after the
  bit law, before the state changes) the sum of the boundary and integral quantities of that sub-step;
  after the loop one column of the global ``AVDW_REC`` (sub-step means and the last sub-step's bit law).
  These lines only read the function's variables and write their own.
  With ``norecord`` the file is left as published (used to check that the recording changes no number).
* ``MAIN.m`` -> ``MAIN_headless.m``: with ``--t1`` the end time ``T1 = 25;`` is replaced (the long runs);
  the drawing lines (setFigs, set(...), drawnow, the figure after the
  loop) are commented out with ``% [headless]``.
* ``--stability``: ``MAIN_Torsional_FreqStabMap.m`` (folder ``Coupled - nondim``) ->
  ``MAIN_Torsional_FreqStabMap_headless.m``, its drawing lines (figure, contourf, colorbar, set, labels,
  xlim, setLatexLabels2, hold on, plot) commented out; the map and ``OmLine`` are computed unchanged.
"""

from __future__ import annotations

import sys
from pathlib import Path

NACC = 21  # sub-step sums recorded (run_reference.m names them with the last sub-step's bit law)

INIT = f"""    global AVDW_REC AVDW_K % [record]
    if isempty(AVDW_K), AVDW_K = 0; end % [record]
    AVDW_K = AVDW_K + 1; avdw_acc = zeros(1, {NACC}); % [record]
"""

ACC = """        avdw_va = (Abeta+Aalpha)/2; avdw_ot = (Tbeta+Talpha)/2; % [record]
        avdw_ha = (Aalpha-Abeta)/(2*p.c_a); avdw_ft = (Talpha-Tbeta)/(2*p.c_t); % [record]
        avdw_F = p.Ap*p.E*(Aalpha0-Abeta(1))/(2*p.c_a); avdw_T = p.Jp*p.G*(Talpha0-Tbeta(1))/(2*p.c_t); % [record]
        avdw_vf = (Aalpha(p.P)+AbetaPp1)/2; avdw_of = (Talpha(p.P)+TbetaPp1)/2; % [record]
        avdw_acc = avdw_acc + [avdw_F, avdw_T, wb, tb, avdw_vf, avdw_of, wb*avdw_vf, tb*avdw_of, ... % [record]
            sum(avdw_va)*dx, sum(avdw_ot)*dx, sum(avdw_va.^2)*dx, sum(avdw_ot.^2)*dx, ... % [record]
            avdw_F*(Aalpha0+Abeta(1))/2, avdw_T*(Talpha0+Tbeta(1))/2, vb, ob, d, ... % [record]
            p.Ap*p.E/2*sum(avdw_ha.^2)*dx, p.Jp*p.G/2*sum(avdw_ft.^2)*dx, ... % [record]
            p.rho*p.Ap/2*sum(avdw_va.^2)*dx, p.rho*p.Jp/2*sum(avdw_ot.^2)*dx]; % [record]
"""

SAVE = """    AVDW_REC(:, AVDW_K) = [avdw_acc/n, wb, tb, vb, ob, d, ga, g_tt, g_wt, wc, tc, wf, tf, n, dt, dxl].'; % [record]
"""


def replace_once(text: str, old: str, new: str, what: str) -> str:
    if text.count(old) != 1:
        raise SystemExit(f"{what}: expected exactly one {old!r}, found {text.count(old)}")
    return text.replace(old, new)


def insert_before(text: str, anchor: str, block: str, what: str) -> str:
    if text.count(anchor) < 1:
        raise SystemExit(f"{what}: anchor {anchor!r} not found")
    i = text.index(anchor)
    return text[:i] + block + text[i:]


def stability(work: Path) -> None:
    """MAIN_Torsional_FreqStabMap.m -> MAIN_Torsional_FreqStabMap_headless.m: drawing lines commented out."""
    draw = ("figure(", "contourf(", "colorbar", "set(", "l = ylabel(", "l = xlabel(", "xlim(",
            "setLatexLabels2(", "hold on", "plot(")
    src = (work / "MAIN_Torsional_FreqStabMap.m").read_text().replace("\r\n", "\n")
    out = []
    for line in src.split("\n"):
        s = line.strip()
        if s and not s.startswith("%") and s.startswith(draw):
            out.append("% [headless] " + line)
        else:
            out.append(line)
    (work / "MAIN_Torsional_FreqStabMap_headless.m").write_text("\n".join(out))


def main() -> None:
    if sys.argv[1] == "--stability":
        stability(Path(sys.argv[2]))
        return
    work = Path(sys.argv[1])
    rpm, rop = sys.argv[2], sys.argv[3]
    rest = sys.argv[4:]
    t1 = rest[rest.index("--t1") + 1] if "--t1" in rest else None
    par = (work / "parameters.m").read_text()
    par = replace_once(par, "p.omega0 = 30/60*2*pi;", f"p.omega0 = {rpm}/60*2*pi;", "parameters.m")
    par = replace_once(par, "p.V0 = 30/3600;", f"p.V0 = {rop}/3600;", "parameters.m")
    (work / "parameters.m").write_text(par)

    if "norecord" not in rest:
        ws = (work / "waveStep_transportBRI.m").read_text()
        ws = insert_before(ws, "    t = 0;\n    for i=1:n\n", INIT, "waveStep_transportBRI.m")
        ws = insert_before(ws, "        %% 1st order Upwind\n", ACC, "waveStep_transportBRI.m")
        ws = insert_before(ws, "    %%\n    v = 1/2         *(Abeta+Aalpha);\n", SAVE, "waveStep_transportBRI.m")
        (work / "waveStep_transportBRI.m").write_text(ws)

    out = []
    after_loop = False
    continued = False  # the line before was commented out and ends with '...'
    draw = ("set(", "drawnow", "figure(", "clf", "plot(", "hold ", "l = legend(", "title(", "xlabel(",
            "ylabel(", "xlim(")
    for line in (work / "MAIN.m").read_text().split("\n"):
        s = line.strip()
        if s.startswith("% Axial limit cycle period"):
            after_loop = True
        if continued or s == "[hAx,hBx] = setFigs(p);" or (s and not s.startswith("%") and s.startswith(draw)):
            out.append("% [headless] " + line)
            continued = s.endswith("...")
            continue
        out.append(line)
    assert after_loop, "MAIN.m: end of the time loop not found"
    main = "\n".join(out)
    if t1 is not None:
        main = replace_once(main, "T1 = 25;", f"T1 = {t1};", "MAIN.m")
    (work / "MAIN_headless.m").write_text(main)


if __name__ == "__main__":
    main()
