function y = db(x)
% Stand-in for MATLAB's db (Signal Processing Toolbox; not in Octave's core), used by
% MAIN_Torsional_FreqStabMap.m:46 on a gain: 20*log10(|x|), MATLAB's default 'voltage' form.
y = 20 * log10(abs(x));
end
