#!/usr/bin/env bash
# Runs raygine's benchmarks (../shared/BENCHMARK.md) in release and prints one line per figure
# plus tables: the comparison with obvhs and Embree 3, then core (build, W1-W3, bytes/tri, L3),
# render (the whole `raygine render` command) and interactive (L1, L2, restart storm).
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
[ ${#steps[@]} -gt 0 ] || steps=(compare core render interactive)
for step in "${steps[@]}"; do
    echo "== raybench $step"
    ./target/release/raybench "$step"
done
