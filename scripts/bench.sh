#!/usr/bin/env bash
# Runs raygine's benchmarks (../shared/BENCHMARK.md) in release and prints one line per figure
# plus tables: the comparison with obvhs and Embree 3, then core (build, W1-W3, bytes/tri, L3),
# render (the whole `raygine render` command), interactive (L1, L2, restart storm), frames
# (F1, F2: whole frames beside Mitsuba 3) and g1 (equal-time GI beside Mitsuba 3).
#
#   scripts/bench.sh                 # everything
#   scripts/bench.sh compare core    # some of it
#
# Needs Debian's libembree-dev for the Embree peer; installs it when missing (as root).
# RAYGINE_SHARED points at the shared folder (default: ../shared beside the repository).
set -euo pipefail
cd "$(dirname "$0")/.."

shared="${RAYGINE_SHARED:-$(pwd)/../shared}"
if [ ! -d "$shared/scenes" ]; then
    echo "bench.sh: skipped: the shared folder ($shared/scenes) is absent; set RAYGINE_SHARED"
    exit 0
fi
export RAYGINE_SHARED="$shared"

features="obvhs"
if [ -f /usr/include/embree3/rtcore.h ]; then
    features="embree,obvhs"
elif [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    apt-get update -qq && apt-get install -y -qq libembree-dev >/dev/null
    features="embree,obvhs"
else
    echo "bench.sh: libembree-dev is missing and cannot be installed (not root): Embree skipped"
fi

cargo build --release -p raygine -p raybench --features "raybench/$features"
steps=("$@")
[ ${#steps[@]} -gt 0 ] || steps=(compare core render interactive frames g1)

# The frames and g1 steps run Mitsuba 3 beside raygine: a venv with mitsuba and numpy, and
# Debian's libllvm19 for its llvm_ad_rgb variant (BENCHMARK.md). Installed here when missing.
if [[ " ${steps[*]} " =~ " "(frames|g1)" " ]] && [ -z "${MITSUBA_PYTHON:-}" ]; then
    venv="${MITSUBA_VENV:-/work/mitsuba-venv}"
    if [ ! -f /usr/lib/x86_64-linux-gnu/libLLVM-19.so ] && [ "$(id -u)" = 0 ]; then
        apt-get update -qq && apt-get install -y -qq libllvm19 >/dev/null
    fi
    if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import mitsuba, numpy" 2>/dev/null; then
        python3 -m venv "$venv" && "$venv/bin/pip" install -q mitsuba numpy ||
            echo "bench.sh: could not install mitsuba into $venv: frames runs raygine alone"
    fi
    export MITSUBA_PYTHON="$venv/bin/python"
fi
# G1 (equal-time global illumination on the Cornell box, 160x120): relative RMSE against a
# 16,384-spp Mitsuba light-tracer reference, made once (about 150-300 s on 2 cores) into
# $G1_REF; then raygine (bdpt, path) and Mitsuba (ptracer, path) get G1_SECONDS each.
g1() {
    local ref="${G1_REF:-/work/ref/cornell_160x120_ptracer.exr}"
    if [ -z "${MITSUBA_PYTHON:-}" ] || ! "$MITSUBA_PYTHON" -c "import mitsuba" 2>/dev/null; then
        echo "# G1 skipped: no Python with mitsuba"
        return
    fi
    if [ ! -f "$ref" ]; then
        echo "# G1: making the reference $ref (ptracer, 16384 spp)"
        mkdir -p "$(dirname "$ref")"
        "$MITSUBA_PYTHON" scripts/mitsuba/cornell_scene.py --integrator ptracer --spp 16384 \
            --seed 0 --out "$ref"
    fi
    # shellcheck disable=SC2086
    MITSUBA_PY="$MITSUBA_PYTHON" G1_REF="$ref" RUNS="${G1_RUNS:-1}" \
        scripts/mitsuba/g1_equal_time.sh ${G1_SECONDS:-20}
}

for step in "${steps[@]}"; do
    echo "== raybench $step"
    if [ "$step" = g1 ]; then
        g1
    else
        ./target/release/raybench "$step"
    fi
done
