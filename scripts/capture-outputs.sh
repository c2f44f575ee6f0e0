#!/usr/bin/env bash
# Captures the --json, CSV and UFF outputs of every command on the shipped
# models (models/*.json and the built-in ones) into OUTDIR, one folder per
# model, one file per output (plus each run's stderr and exit code).
# Run it before and after a change to the output code and compare the two
# folders with scripts/compare-outputs.py (numbers to 1e-12 relative,
# provenance excluded).
#
#   scripts/capture-outputs.sh OUTDIR [BINARY]
set -uo pipefail
out=${1:?usage: capture-outputs.sh OUTDIR [BINARY]}
bin=${2:-target/release/ancf-modal}
bin=$(realpath "$bin")
cd "$(dirname "$0")/.."
mkdir -p "$out"
out=$(cd "$out" && pwd)

# run NAME DIR ARGS...: runs the binary in DIR with ARGS, stdout to NAME.out.
run() {
    local name=$1 dir=$2
    shift 2
    (cd "$dir" && "$bin" "$@" >"$name.out" 2>"$name.err"; echo $? >"$name.rc")
}

for model in builtin models/*.json; do
    tag=$(basename "$model" .json)
    dir=$out/$tag
    mkdir -p "$dir"
    m=()
    [ "$model" != builtin ] && m=("$PWD/$model")
    run modal "$dir" modal "${m[@]}" --json --csv modal.csv --uff modal.uff
    run modal_dense "$dir" modal "${m[@]}" --json --solver dense --modes 8
    run modal_prestress "$dir" modal "${m[@]}" --json --prestress --csv modal_prestress.csv
    run modal_sweep_load "$dir" modal "${m[@]}" --json --sweep-load 0:1:3 --csv modal_sweep_load.csv
    run modal_mac "$dir" modal "${m[@]}" --json --mac "$dir/modal.uff"
    run static "$dir" static "${m[@]}" --json
    run impulse "$dir" impulse "${m[@]}" --json --end-time 0.02 --csv impulse.csv --uff impulse.uff
    run transient "$dir" transient "${m[@]}" --json --end-time 0.002 --csv transient.csv --uff transient.uff
    run transient_eq "$dir" transient "${m[@]}" --json --end-time 0.001 --from-equilibrium
    run switch_off "$dir" switch-off "${m[@]}" --json --end-time 0.001 --csv switch_off.csv --compare-rigid
    run calibrate "$dir" calibrate "${m[@]}" --json --target 4600
    run calibrate_mk "$dir" calibrate "${m[@]}" --json --target 4600,11300 --mode 1,2 --param height --param width
    run convergence "$dir" convergence "${m[@]}" --json --max-elements 16 --modes 2
    run sweep "$dir" sweep "${m[@]}" --json --param 'height=0.9e-3:1.2e-3:3' --quantity first_bending_hz --csv sweep.csv
    run sweep_freq "$dir" sweep "${m[@]}" --json --param 'height=0.9e-3:1.2e-3:2' --param 'width=5e-3:6e-3:2' --quantity frequency:2 --csv sweep_freq.csv
    run sweep_s1 "$dir" sweep "${m[@]}" --json --param 'height=0.9e-3:1.2e-3:3' --quantity first_bending_hz --shard 1/2
    run sweep_s2 "$dir" sweep "${m[@]}" --json --param 'height=0.9e-3:1.2e-3:3' --quantity first_bending_hz --shard 2/2
    run sweep_merge "$dir" sweep-merge sweep_s1.out sweep_s2.out --json --csv sweep_merge.csv
    run frf "$dir" frf impulse.uff --json --csv frf.csv --uff frf.uff
    sensor=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['sensors'][0]['id'])" "${m[@]:-src/model/default.json}" 2>/dev/null || echo vibrometer)
    if [ "$model" = builtin ]; then mm=(--model "$PWD/models/rcbo_free_free.json"); else mm=(--model "$PWD/$model"); fi
    run frf_model "$dir" frf impulse.uff --json "${mm[@]}" --at "$sensor"
    run identify "$dir" identify "${m[@]}" --json --end-time 0.02
    run identify_dir "$dir" identify "${m[@]}" --end-time 0.02 --calibrate --out-dir identify_dir
    run identify_measured "$dir" identify "${m[@]}" --json --end-time 0.02 --measured impulse.uff
done
# the built-in switch-off assembly, and a sweep of its transient quantity
dir=$out/builtin
run sweep_time "$dir" sweep --json --quantity time_to_distance_s --param 'load_scale:F_x2=1:1.2:2' --end-time 0.001
# figures are not compared (their text holds no numbers the JSON lacks)
find "$out" \( -name '*.svg' -o -name '*.png' \) -delete
