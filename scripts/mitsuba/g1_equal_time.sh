#!/usr/bin/env bash
# BENCHMARK.md G1: the built-in Cornell box at 160x120, relative RMSE against Mitsuba's 16,384-spp
# light-tracer reference after T seconds, for raygine (bdpt, light, path) and Mitsuba 3 (ptracer,
# path), interleaved so that all see the same machine. One line per run, with the reported
# error (raygine's "remaining noise") beside the measured one:
#   G1 scene=cornell lib=raygine-bdpt threads=2 res=160x120 seconds=20 spp=1255 rel_rmse=0.0236 reported=0.0231
# Usage: scripts/mitsuba/g1_equal_time.sh [SECONDS...]   (default 5 20 60; RUNS=3)
# LIBS picks renderers (default "raygine-bdpt raygine-light mitsuba-ptracer raygine-path
# mitsuba-path"). E3=1 runs BENCHMARK.md's E3 instead: the light at y = 500 mm
# (cornell_e3.raygine.toml), against $E3_REF (default /work/ref/cornell_e3_160x120_path.exr).
# Needs the Mitsuba venv of scripts/mitsuba/README.md ($MITSUBA_PY, default
# /work/mitsuba-venv/bin/python) and the reference ($G1_REF, default
# /work/ref/cornell_160x120_ptracer.exr; the README says how to make it).
set -euo pipefail
cd "$(dirname "$0")/../.."
PY="${MITSUBA_PY:-/work/mitsuba-venv/bin/python}"
REF="${G1_REF:-/work/ref/cornell_160x120_ptracer.exr}"
NAME=G1
SIDECAR_ARGS=()
if [ "${E3:-0}" = 1 ]; then
    NAME=E3
    REF="${E3_REF:-/work/ref/cornell_e3_160x120_path.exr}"
    SIDECAR_ARGS=(--sidecar scripts/mitsuba/cornell_e3.raygine.toml)
fi
LIBS="${LIBS:-raygine-bdpt raygine-light mitsuba-ptracer raygine-path mitsuba-path}"
RUNS="${RUNS:-3}"
THREADS="${THREADS:-$(nproc)}"
[ -x "$PY" ] || { echo "g1: no Mitsuba python at $PY (scripts/mitsuba/README.md)"; exit 1; }
[ -f "$REF" ] || { echo "g1: no reference at $REF (scripts/mitsuba/README.md)"; exit 1; }
export DRJIT_LIBLLVM_PATH="${DRJIT_LIBLLVM_PATH:-/usr/lib/x86_64-linux-gnu/libLLVM-19.so}"
cargo build --release -q -p raygine
BIN=target/release/raygine
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
rmse() { "$PY" scripts/mitsuba/g1_rmse.py "$REF" "$1" | sed -n '1s/.*rmse_rel=\([0-9.]*\).*/\1/p'; }
secs_list=("$@")
[ ${#secs_list[@]} -gt 0 ] || secs_list=(5 20 60)
for secs in "${secs_list[@]}"; do
    for run in $(seq 1 "$RUNS"); do
        for lib in $LIBS; do
            img="$OUT/$lib-$secs-$run.exr"
            reported=
            case "$lib" in
            raygine-*)
                "$BIN" render "${SIDECAR_ARGS[@]}" --integrator "${lib#raygine-}" \
                    --time-limit "$secs" --samples 1048576 --threads "$THREADS" -W 160 -H 120 \
                    -R "$OUT/x.png" --exr "$img" >"$OUT/log"
                spp=$(sed -n 's/.* \([0-9]*\) spp.*/\1/p' "$OUT/log" | head -1)
                reported=$(sed -n 's/^remaining noise: \([0-9.]*\) %.*/\1/p' "$OUT/log") ;;
            mitsuba-*)
                spp=$("$PY" scripts/mitsuba/cornell_scene.py "${SIDECAR_ARGS[@]}" \
                    --integrator "${lib#mitsuba-}" --seconds "$secs" --seed "$run" \
                    --threads "$THREADS" --out "$img" |
                    sed -n 's/.*spp=\([0-9]*\).*/\1/p' | tail -1) ;;
            esac
            line="$NAME scene=cornell lib=$lib threads=$THREADS res=160x120 seconds=$secs run=$run spp=$spp rel_rmse=$(rmse "$img")"
            [ -z "$reported" ] || line="$line reported=$(awk "BEGIN { print $reported / 100 }")"
            echo "$line"
        done
    done
done
