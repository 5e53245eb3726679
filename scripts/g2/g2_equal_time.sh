#!/usr/bin/env bash
# G2 equal time (../shared/BENCHMARK.md): room2 (with scripts/g2/room2_g2.raygine.toml) at
# 320x194, every renderer given T seconds on THREADS threads, RUNS interleaved rounds
# (A B C ... A B C ...), each image scored with g2_rmse.py against REF.
#
#   T=20 RUNS=3 REF=/work/ref/room2_g2_ref.exr scripts/g2/g2_equal_time.sh
#
# LIBS picks from: raygine-bdpt raygine-bdpt-noadapt raygine-path mitsuba-ptracer mitsuba-path
# cycles-path. Images and logs go to OUT (default /tmp/g2_equal). Needs the release raygine and
# raybench of this tree, /work/mitsuba-venv and /work/venv-bpy.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
T=${T:-20}
RUNS=${RUNS:-3}
THREADS=${THREADS:-2}
OUT=${OUT:-/tmp/g2_equal}
SCENE=${SCENE:-$root/../shared/scenes/ipur-room2/room2.shp}
SIDECAR=${SIDECAR:-$here/room2_g2.raygine.toml}
LIBS=${LIBS:-"raygine-bdpt raygine-bdpt-noadapt raygine-path mitsuba-ptracer mitsuba-path cycles-path"}
MPY=${MPY:-/work/mitsuba-venv/bin/python}
BPY=${BPY:-/work/venv-bpy/bin/python}
export DRJIT_LIBLLVM_PATH=${DRJIT_LIBLLVM_PATH:-/usr/lib/x86_64-linux-gnu/libLLVM-19.so}
RG=$root/target/release/raygine
mkdir -p "$OUT"
dump=$OUT/dump
"$root/target/release/raybench" scene-dump -S "$SCENE" --sidecar "$SIDECAR" --out "$dump" >/dev/null 2>&1

echo "cpu: $(grep -o 'avx512[a-z_]*' /proc/cpuinfo | sort -u | tr '\n' ' ')"
for run in $(seq 1 "$RUNS"); do
  for lib in $LIBS; do
    img=$OUT/${lib}_T${T}_run$run.exr
    log=$OUT/${lib}_T${T}_run$run.log
    start=$(date +%s.%N)
    case $lib in
      raygine-bdpt | raygine-bdpt-noadapt | raygine-path)
        gi=${lib#raygine-}; gi=${gi%-noadapt}
        extra=(); [[ $lib == *noadapt ]] && extra=(--no-adaptive)
        "$RG" render -S "$SCENE" --sidecar "$SIDECAR" -W 320 -H 194 --gi "$gi" --threads "$THREADS" \
          --time-limit "$T" "${extra[@]}" -R "$OUT/tmp.png" --exr "$img" >"$log" 2>&1 ;;
      mitsuba-ptracer | mitsuba-path)
        "$MPY" "$here/room2_mitsuba.py" "$dump" --integrator "${lib#mitsuba-}" --seconds "$T" \
          --threads "$THREADS" --seed "$run" --out "$img" >"$log" 2>&1 ;;
      cycles-path)
        "$BPY" "$here/room2_cycles.py" "$dump" --time "$T" --threads "$THREADS" --seed "$run" \
          --out "$img" >"$log" 2>&1 ;;
      *) echo "unknown lib $lib" >&2; exit 2 ;;
    esac
    wall=$(echo "$(date +%s.%N) - $start" | bc)
    # the renderer's own figure of what it rendered (render time, samples)
    case $lib in
      raygine-*) own="$(grep -o 'px, [0-9.]* spp' "$log" | tail -1) $(grep -o 'rendered in [0-9.]* ms' "$log" | head -1)" ;;
      mitsuba-*) own=$(grep -o 'spp=[0-9]* seconds=[0-9.]*' "$log" | head -1) ;;
      cycles-*) own=$(grep -o 'render_call_s=[0-9.]* .*cycles_render=[0-9:.]*' "$log" | head -1) ;;
    esac
    echo "G2 lib=$lib threads=$THREADS res=320x194 seconds=$T run=$run wall_s=$wall own=[$own] img=$img"
  done
done
if [[ -n ${REF:-} ]]; then
  for lib in $LIBS; do
    "$MPY" "$here/g2_rmse.py" "$REF" "$OUT/${lib}"_T"${T}"_run*.exr
  done
fi
