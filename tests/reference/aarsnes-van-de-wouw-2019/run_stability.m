% Linear torsional stability of Aarsnes & van de Wouw's model, headless. Called by make_reference.sh in a
% temporary directory holding MAIN_Torsional_FreqStabMap_headless.m (their "Coupled - nondim" script with
% the drawing commented out by make_headless.py --stability), Coupled/parameters.m, and the stand-ins
% nyqStab.m and db.m of this directory. Environment: AVDW_OUT (output directory).
%
% 1. Their non-dimensional map, unchanged: Gt(s) = -gt(s)/s * V0/Om * (1 - exp(-s/Om)),
%    gt = (1 + Z tanh s)/(Z + tanh s), Z = (1+eta)/(1-eta), eta = 0.7; Z(i,j) = max gain at -180 deg;
%    OmLine(i) = the largest Om of the unstable band at low Om for each V0 (their lines 74-80).
% 2. The dimensional loop of Coupled/freqPlots.m (lines 17-36) at the parameters of Coupled/parameters.m:
%    Gt(s) = gt(s) Kt/s (1 - exp(-s tN)), gt = -tanh(L s/c_t sqrt(1 + kt/s)) / sqrt(1 + kt/s),
%    Ga(s) = -ga(s) Ka/s (1 - exp(-s tN)) likewise, swept over the rotary speed at 30 and 60 m/h, with the
%    damping rate kt as named (freqPlots.m) and 2 kt (the rate the time stepping applies).
MAIN_Torsional_FreqStabMap_headless;
outdir = getenv('AVDW_OUT');
fid = fopen(fullfile(outdir, 'stability_nondim.csv'), 'w');
fprintf(fid, 'V0,OmLine\n');
fprintf(fid, '%.17g,%.17g\n', [V0Vect(:), OmLine(:)].');
fclose(fid);
fid = fopen(fullfile(outdir, 'stability_nondim_Z.csv'), 'w');   % rows: V0Vect, columns: OmVec
fprintf(fid, '%s\n', ['V0\Om,' strjoin(arrayfun(@(v) sprintf('%.17g', v), OmVec, 'UniformOutput', false), ',')]);
fprintf(fid, [repmat('%.17g,', 1, numel(OmVec)) '%.17g\n'], [V0Vect(:), Z].');
fclose(fid);
printf('[headless] eta = %g, %d x %d map\n', eta, numel(V0Vect), numel(OmVec));

p0 = parameters();
nw = 2e4;                       % freqPlots.m: nw = 2e3 on the same interval
w = linspace(3e-3, 10*2*pi, nw)';
s = 1j*w;
rpmVec = [linspace(5, 300, 591)'; 30; 60; 120];
ropVec = [30 60];
rows = [];
for rop = ropVec
  for rpm = rpmVec.'
    p = p0;
    p.omega0 = rpm/60*2*pi; p.V0 = rop/3600;
    % the derived quantities as parameters.m computes them (its lines 33, 46, 48, 51, 52)
    p.dNom = (2*pi)*p.V0/(p.omega0*p.N);
    p.tN = 2*pi/(p.N*p.omega0);
    p.R = p.V0/p.omega0;
    p.Ka = p.a*p.zeta*p.epsilon*p.N /(  p.Ap*sqrt(p.E*p.rho));
    p.Kt =  p.R*p.a^2*p.epsilon*p.N /(2*p.Jp*sqrt(p.G*p.rho));
    out = [rpm, rop, p.tN, p.Ka, p.Kt];
    for damp = [1 2]
      ka = damp*p.ka; kt = damp*p.kt;
      % freqPlots.m lines 17-23, 30, 35, 36
      Zca  =      1/p.c_a.*sqrt(1 + ka./(s));
      Gap  = p.L *s/p.c_a.*sqrt(1 + ka./(s));
      Zct  =      1/p.c_t.*sqrt(1 + kt./(s));
      Gtp  = p.L *s/p.c_t.*sqrt(1 + kt./(s));
      ga = -1/p.c_a* 1./Zca.*tanh(Gap);
      gt = -1/p.c_t* 1./Zct.*tanh(Gtp);
      delay = (1-exp(-s*p.tN));
      Ga =  -ga .*p.Ka./s.*delay;
      Gt =   gt .*p.Kt./s.*delay;
      [~, dGt, wt] = nyqStab(Gt, w);
      [~, dGa, wa] = nyqStab(Ga, w);
      [~, dG, wg] = nyqStab(Ga + Gt, w);
      if isempty(dGt), dGt = 0; wt = NaN; end
      if isempty(dGa), dGa = 0; wa = NaN; end
      if isempty(dG), dG = 0; wg = NaN; end
      out = [out, dGt(1), wt, dGa(1), wa, dG(1), wg];
    end
    rows = [rows; out];
  end
end
fid = fopen(fullfile(outdir, 'stability_dimensional.csv'), 'w');
fprintf(fid, ['rpm,rop_m_per_h,tN_s,Ka_1_s,Kt_1_s,' ...
  'MT_named,wT_named_rad_s,MA_named,wA_named_rad_s,MG_named,wG_named_rad_s,' ...
  'MT_2k,wT_2k_rad_s,MA_2k,wA_2k_rad_s,MG_2k,wG_2k_rad_s\n']);
fprintf(fid, [repmat('%.17g,', 1, columns(rows) - 1) '%.17g\n'], rows.');
fclose(fid);
printf('[headless] dimensional loop: %d rows\n', rows(end, 1));
