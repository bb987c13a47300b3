#!/bin/sh
# Regenerate series.csv, final_state.csv, scalars.csv, profiles.csv of this directory with GNU Octave.
# usage: sh run_octave.sh <git dir of Open-Source-Drilling-Community/Aarsnes-and-Shor-Torsional-Model>
set -eu
SRC=${1:?git dir of the Aarsnes-and-Shor-Torsional-Model repository}
COMMIT=67002405b46a8f70dec3f25c2211fcb9a9db23f8
HERE=$(cd "$(dirname "$0")" && pwd)
WORK=$(mktemp -d)
for f in MAIN.m parameters_WellB.m torsionalWaveStep.m setFigs.m; do
    git -C "$SRC" show "$COMMIT:$f" > "$WORK/$f"
done
python3 "$HERE/make_headless.py" "$WORK/MAIN.m" > "$WORK/MAIN_headless.m"
cd "$WORK"
AS_OUT="$HERE" octave-cli --no-window-system -q --eval 'MAIN_headless'
rm -rf "$WORK"
