#!/bin/sh
# Regenerate the reference data of this directory with GNU Octave from Aarsnes & van de Wouw's published code.
# usage: sh make_reference.sh <git dir of ulfjakob/AxialTorsionalDrillString> [RAW_DIR]
# Reads the code at COMMIT with `git show` (nothing is downloaded), runs the six cases of the dimensional
# coupled model (Coupled/) to 25 s (and the 30 rpm ones to 120 s) and the torsional stability map (Coupled - nondim/), writes the full-resolution
# CSV files to RAW_DIR (default: a temporary directory, removed at the end) and then, from them,
# reference.npz and reference.json here (make_reference.py).
set -eu
SRC=${1:?git dir of the AxialTorsionalDrillString repository}
COMMIT=934481490111bb9101da743f525d35723282f72c
HERE=$(cd "$(dirname "$0")" && pwd)
RAW=${2:-}
KEEP=1
if [ -z "$RAW" ]; then RAW=$(mktemp -d); KEEP=0; fi
mkdir -p "$RAW"
RAW=$(cd "$RAW" && pwd)

export_coupled() {  # $1: directory
    for f in MAIN.m parameters.m waveStep_transportBRI.m; do
        git --git-dir="$SRC" show "$COMMIT:Coupled/$f" > "$1/$f"
    done
}

run_case() {  # $1: name prefix ("" or "long_"), $2: rpm, $3: ROP m/h, then extra make_headless.py arguments
    prefix=$1; rpm=$2; rop=$3; shift 3
    WORK=$(mktemp -d)
    export_coupled "$WORK"
    python3 "$HERE/make_headless.py" "$WORK" "$rpm" "$rop" "$@"
    cp "$HERE/run_reference.m" "$WORK/"
    start=$(date +%s.%N)
    (cd "$WORK" && AVDW_OUT="$RAW" AVDW_CASE="${prefix}rpm${rpm}_rop${rop}" octave-cli --no-window-system -q --eval run_reference)
    end=$(date +%s.%N)
    echo "${prefix}rpm${rpm}_rop${rop},$(echo "$end - $start" | bc)" >> "$RAW/wall_seconds.csv"
    rm -rf "$WORK"
}

# The six cases as MAIN.m runs them (T1 = 25 s), then the two 30 rpm cases run to T1 = 120 s (their
# transient from the initial profiles lasts longer than 25 s; the long runs show where they go).
for c in 30:30 30:60 60:30 60:60 120:30 120:60; do
    run_case "" "${c%%:*}" "${c##*:}"
done
for c in 30:30 30:60; do
    run_case "long_" "${c%%:*}" "${c##*:}" --t1 120
done

# The recording lines change no number: the published waveStep_transportBRI.m, unchanged, gives the same
# final state and outputs y at 30 rpm / 30 m/h, compared exactly.
WORK=$(mktemp -d)
export_coupled "$WORK"
python3 "$HERE/make_headless.py" "$WORK" 30 30 norecord
(cd "$WORK" && octave-cli --no-window-system -q --eval "MAIN_headless; xe = x(:, end); fid = fopen('$RAW/unrecorded_rpm30_rop30.csv', 'w'); fprintf(fid, '%.17g\n', [xe; y(:)]); fclose(fid);")
rm -rf "$WORK"

# Torsional stability map of the non-dimensional model (MAIN_Torsional_FreqStabMap.m) and the
# dimensional transfer functions of Coupled/freqPlots.m swept over the rotary speed.
WORK=$(mktemp -d)
git --git-dir="$SRC" show "$COMMIT:Coupled - nondim/MAIN_Torsional_FreqStabMap.m" > "$WORK/MAIN_Torsional_FreqStabMap.m"
git --git-dir="$SRC" show "$COMMIT:Coupled/parameters.m" > "$WORK/parameters.m"
cp "$HERE/nyqStab.m" "$HERE/db.m" "$HERE/run_stability.m" "$WORK/"
python3 "$HERE/make_headless.py" --stability "$WORK"
(cd "$WORK" && AVDW_OUT="$RAW" octave-cli --no-window-system -q --eval run_stability)
rm -rf "$WORK"

python3 "$HERE/make_reference.py" "$RAW"
if [ "$KEEP" = 0 ]; then rm -rf "$RAW"; fi
