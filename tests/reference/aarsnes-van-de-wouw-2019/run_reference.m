% Run one case of Aarsnes & van de Wouw's dimensional coupled model headless and write it as CSV.
% Called by make_reference.sh inside a temporary directory holding their Coupled/ files as prepared by
% make_headless.py (parameters.m with this case's RPM and ROP, waveStep_transportBRI.m with the recording
% lines, MAIN_headless.m). Environment: AVDW_OUT (output directory), AVDW_CASE (file name stem).
% Writes <stem>_series.csv (one row per 0.003 s step), <stem>_final.csv (the final state x(:,end)) and
% <stem>_scalars.csv (the parameter struct p and scheme constants).
MAIN_headless;   % their MAIN.m, drawing commented out; starts with clear
global AVDW_REC AVDW_K
outdir = getenv('AVDW_OUT');
stem = getenv('AVDW_CASE');
names = {'top_force_N','top_torque_Nm','wob_N','tob_Nm','bit_face_speed_m_s','bit_face_speed_rad_s', ...
  'bit_axial_power_W','bit_torsional_power_W','axial_momentum_m2_s','angular_momentum_m_rad_s', ...
  'axial_speed_sq_int_m3_s2','angular_speed_sq_int_m_rad2_s2','top_axial_power_W','top_torsional_power_W', ...
  'bit_cell_speed_m_s','bit_cell_speed_rad_s','depth_of_cut_m','axial_strain_energy_J', ...
  'torsional_strain_energy_J','axial_kinetic_energy_J','torsional_kinetic_energy_J', ...
  'last_wob_N','last_tob_Nm','last_vb_m_s','last_ob_rad_s','last_d_m','last_ga','last_g_tt_Nm', ...
  'last_g_wt_N','last_wc_N','last_tc_Nm','last_wf_N','last_tf_Nm','substeps','dt_sub_s','dxl'};
assert(AVDW_K == Nt && rows(AVDW_REC) == numel(names));
P = p.P; dx = p.L/p.P;
xe = x(:, 2:Nt+1);                      % state after step k (time t(k) + p.dt)
h = xe(1:P,:); v = xe(P+1:2*P,:); f = xe(2*P+1:3*P,:); o = xe(3*P+1:4*P,:);
% step-end integrals of the state (same expressions as the recording lines)
E_end = [p.Ap*p.E/2*sum(h.^2)*dx; p.Jp*p.G/2*sum(f.^2)*dx; p.rho*p.Ap/2*sum(v.^2)*dx; p.rho*p.Jp/2*sum(o.^2)*dx];
M_end = [sum(v)*dx; sum(o)*dx];
cols = [t(:), t(:) + p.dt, xe(2*P,:).', xe(4*P,:).', xe(P+1,:).', xe(3*P+1,:).', xe(P,:).', xe(3*P,:).', ...
        xe(1,:).', xe(2*P+1,:).', y(1,2:Nt+1).', y(2,2:Nt+1).', y(3,2:Nt+1).', E_end.', M_end.', AVDW_REC.'];
hdr = ['t_start_s,t_end_s,bit_cell_speed_end_m_s,bit_cell_speed_end_rad_s,top_cell_speed_end_m_s,' ...
       'top_cell_speed_end_rad_s,bit_cell_axial_strain_end,bit_cell_torsional_strain_end,' ...
       'top_cell_axial_strain_end,top_cell_torsional_strain_end,y1_d_m,y2_one_minus_ga,y3_wf_N,' ...
       'axial_strain_energy_end_J,torsional_strain_energy_end_J,axial_kinetic_energy_end_J,' ...
       'torsional_kinetic_energy_end_J,axial_momentum_end_m2_s,angular_momentum_end_m_rad_s,' ...
       strjoin(names, ',')];
fid = fopen(fullfile(outdir, [stem '_series.csv']), 'w');
fprintf(fid, '%s\n', hdr);
fmt = [repmat('%.17g,', 1, columns(cols) - 1) '%.17g\n'];
fprintf(fid, fmt, cols.');
fclose(fid);
fid = fopen(fullfile(outdir, [stem '_final.csv']), 'w');
fprintf(fid, 'x_end\n');
fprintf(fid, '%.17g\n', x(:, end));
fclose(fid);
fid = fopen(fullfile(outdir, [stem '_scalars.csv']), 'w');
fprintf(fid, 'name,value\n');
fn = fieldnames(p);
for i = 1:numel(fn)
  val = p.(fn{i});
  if isscalar(val)
    fprintf(fid, '%s,%.17g\n', fn{i}, val);
  end
end
fprintf(fid, 'Nt,%d\nT1,%.17g\nx_columns,%d\n', Nt, T1, columns(x));
fclose(fid);
printf('[headless] %s: %d steps, Pl = %d, substeps %d\n', stem, Nt, p.Pl, AVDW_REC(end-2, 1));
