# ruff: noqa: E501  (the appended Octave block keeps its long lines)
"""Make MAIN.m of Aarsnes & Shor run headless in Octave: comment out plotting, add a timer and a save block.

Usage: python3 make_headless.py MAIN.m > MAIN_headless.m   (the file keeps its CRLF line ends)
Only lines that draw are commented out (prefixed with '% [headless] '); no numerical line is changed.
"""
import sys

src = open(sys.argv[1], newline="").read().split("\r\n")
DRAW_PREFIXES = ("figure(", "clf", "plotyy(", "    [p.xp;p.xc],[p.P_thresProfile", "title(", "set(",
                 "drawnow", "plot(", "hold on", "l = title(", "ylabel(", "xlabel(")
out = []
after_loop = False
for line in src:
    s = line.strip()
    if s.startswith("%% Finalize Plots"):
        after_loop = True
    if s == "[hAx,hBx,hFig] = setFigs(p,MD);":
        out.append("% [headless] " + line)
        out.append("tsim_start = tic; % [headless] wall-clock timer")
        continue
    if s and not s.startswith("%") and any(s.startswith(pfx.strip()) for pfx in DRAW_PREFIXES):
        out.append("% [headless] " + line)
        continue
    out.append(line)
SAVE = r"""
%% [headless] save the reference series (appended; reads only variables computed above)
tsim = toc(tsim_start);
outdir = getenv('AS_OUT');
bit_idx = 2*Pt;          % last collar cell velocity (x(Pt+p.Pp+p.Pc))
td_idx = 2*Pt+1;         % top-drive velocity
fid = fopen(fullfile(outdir, 'series.csv'), 'w');
fprintf(fid, 't_s,motor_torque_Nm,top_drive_speed_rad_s,bit_speed_rad_s\n');
fprintf(fid, '%.17g,%.17g,%.17g,%.17g\n', [t(:), y(:), x(td_idx,1:Nt).', x(bit_idx,1:Nt).'].');
fclose(fid);
fid = fopen(fullfile(outdir, 'final_state.csv'), 'w');
fprintf(fid, 'x_end\n');
fprintf(fid, '%.17g\n', x(:,end));
fclose(fid);
dxp = p.Lp/p.Pp; dtp = dxp/p.c_t*.99; dxc = p.Lc/p.Pc; dtc = dxc/p.c_t*.99;
nsub = ceil(p.dt/min(dtp,dtc)); dtsub = p.dt/nsub;
fid = fopen(fullfile(outdir, 'scalars.csv'), 'w');
fprintf(fid, 'name,value\n');
names = {'tauMax1','tauMin','phiMax_TD','Jc','Ac','Cro','Jp','Ap','Pro','Pri','Gp','Gc','rho','c_t','kt','I_TD', ...
         'Lp','Lc','Pp','Pc','dxp','dxc','nsub','dtsub','damping_rate_2_kt_dtsub','Nt','x_columns','wall_seconds'};
vals = [tauMax(1), tauMin, phiMax_TD, p.Jc, p.Ac, p.Cro, p.Jp, p.Ap, p.Pro, p.Pri, p.Gp, p.Gc, p.rho, p.c_t, p.kt, p.I_TD, ...
        p.Lp, p.Lc, p.Pp, p.Pc, dxp, dxc, nsub, dtsub, 2*p.kt*dtsub, Nt, columns(x), tsim];
for i = 1:numel(names)
  fprintf(fid, '%s,%.17g\n', names{i}, vals(i));
end
fclose(fid);
fid = fopen(fullfile(outdir, 'profiles.csv'), 'w');
fprintf(fid, 'md_m,inclination_rad,coulomb_torque_per_m_Nm,tauMax_Nm\n');
fprintf(fid, '%.17g,%.17g,%.17g,%.17g\n', [[p.xp;p.xc], [p.PthetaVec;p.CthetaVec], [p.P_thresProfile;p.C_thresProfile], tauMax].');
fclose(fid);
printf('[headless] simulated %g s in %.1f s wall\n', t(end), tsim);
"""
out.append(SAVE.replace("\n", "\r\n"))
sys.stdout.write("\r\n".join(out))
