#!/usr/bin/env bash
# Runs each fuzz target in turn for SECS seconds (default 600) on one core, seeded with the
# committed corpus and, when present, the local seeds from seeds.py. Logs go to logs/<target>.log.
#
#   RUSTC_BOOTSTRAP=1 fuzz/campaign.sh [SECS] [TARGET ...]
set -uo pipefail
cd "$(dirname "$0")"
export RUSTC_BOOTSTRAP=1
secs="${1:-600}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(shp brs sidecar ies ldt atr prb lgt cam part)
mkdir -p logs
for t in "${targets[@]}"; do
    dict=shp.dict
    [ "$t" = sidecar ] && dict=sidecar.dict
    [ "$t" = ies ] && dict=ies.dict
    [ "$t" = ldt ] && dict=ldt.dict
    case "$t" in atr | prb | lgt | cam) dict="$t.dict" ;; esac
    dirs=("corpus/$t")
    [ -d "seeds/$t" ] && dirs+=("seeds/$t")
    echo "== $t: ${secs}s" >&2
    cargo fuzz run "$t" "${dirs[@]}" -- -max_total_time="$secs" -rss_limit_mb=2048 -timeout=10 \
        -dict="$dict" -max_len=8192 -print_final_stats=1 >"logs/$t.log" 2>&1
    echo "== $t: exit $?" >&2
done
