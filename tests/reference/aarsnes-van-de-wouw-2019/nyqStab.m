function [unstab, dG, wu] = nyqStab(G, w, nModes)
% Stand-in for nyqStab.m, which MAIN_Torsional_FreqStabMap.m calls but the published repository does not
% contain. Written from how the repository uses it and from the title of its plot
% ("Inverse gain margin (dB) M_G = max over varpi in varpi_180 of |G_a(j varpi)|", stabilityMap_pipe.m:65):
%   dG     |G(j w)| at every crossing of the negative real axis (phase -180 deg modulo 360 deg), found
%          where imag(G) changes sign between grid points with real(G) < 0, linearly interpolated;
%          sorted from the largest down (ustabModes.m reads the leading nModes entries as the unstable
%          modes while they exceed 1);
%   wu     the frequency of each entry of dG (with two arguments only that of the largest, a scalar,
%          as MAIN_Torsional_FreqStabMap.m stores it into one matrix element);
%   unstab true when the largest exceeds 1 (MAIN_Torsional_FreqStabMap.m: Zss = Z > 1).
G = G(:); w = w(:);
im = imag(G);
i = find((im(1:end-1) .* im(2:end) <= 0) & (im(1:end-1) ~= im(2:end)));
frac = im(i) ./ (im(i) - im(i+1));
Gc = G(i) + frac .* (G(i+1) - G(i));
wc = w(i) + frac .* (w(i+1) - w(i));
keep = real(Gc) < 0;
dG = abs(Gc(keep));
wu = wc(keep);
[dG, order] = sort(dG, 'descend');
wu = wu(order);
if nargin >= 3
  dG = dG(1:min(nModes, end)); wu = wu(1:min(nModes, end));
elseif ~isempty(wu)
  wu = wu(1);
end
unstab = ~isempty(dG) && dG(1) > 1;
end
