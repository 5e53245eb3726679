#!/usr/bin/env bash
# Everything CI checks, in order: formatting, clippy (warnings are errors), every test of the
# workspace, the viewer smoke run under Xvfb, then a sharded render through a local Slurm cluster
# (root only; skipped with the reason otherwise). Run from anywhere: scripts/check.sh
set -euo pipefail
cd "$(dirname "$0")/.."

# Smaller, faster debug builds on 2-core machines (DESKTOP.md).
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"
export CARGO_PROFILE_DEV_DEBUG="${CARGO_PROFILE_DEV_DEBUG:-line-tables-only}"
export CARGO_TERM_COLOR="${CARGO_TERM_COLOR:-never}"

if command -v rustup >/dev/null 2>&1; then
    rustup component add rustfmt clippy >/dev/null 2>&1 ||
        echo "check.sh: could not add rustfmt/clippy with rustup; using what is installed"
fi

echo "== Open Image Denoise for the denoiser's tests (pip, outside the repository)"
if [ -z "${RAYGINE_OIDN:-}" ]; then
    if lib=$(scripts/oidn.sh); then
        export RAYGINE_OIDN="$lib"
        echo "check.sh: RAYGINE_OIDN=$RAYGINE_OIDN"
    elif [ "${CI:-}" = true ]; then
        echo "check.sh: FAIL: CI needs Open Image Denoise (scripts/oidn.sh failed)" >&2
        exit 1
    else
        echo "check.sh: no Open Image Denoise: the denoiser's tests skip with the reason"
    fi
fi
# Tests that need the denoiser fail instead of skipping under CI.
if [ "${CI:-}" = true ]; then
    export RAYGINE_REQUIRE_OIDN=1
fi

echo "== Radiance's evalglare for the glare tests (pip, outside the repository)"
if [ -z "${RAYGINE_EVALGLARE:-}" ]; then
    if exe=$(scripts/evalglare.sh); then
        export RAYGINE_EVALGLARE="$exe"
        echo "check.sh: RAYGINE_EVALGLARE=$RAYGINE_EVALGLARE"
    elif [ "${CI:-}" = true ]; then
        echo "check.sh: FAIL: CI needs evalglare (scripts/evalglare.sh failed)" >&2
        exit 1
    else
        echo "check.sh: no evalglare: the glare comparisons skip with the reason"
    fi
fi
if [ "${CI:-}" = true ]; then
    export RAYGINE_REQUIRE_EVALGLARE=1
fi

echo "== cargo fmt --check"
cargo fmt --all -- --check

echo "== the headless build has no GUI crate"
scripts/check_headless.sh

echo "== cargo clippy (warnings are errors)"
cargo clippy --workspace --all-targets -- -D warnings

echo "== cargo test --workspace"
cargo test --workspace

echo "== viewer smoke run under Xvfb"
if [ -x scripts/smoke_viewer.sh ]; then
    scripts/smoke_viewer.sh
else
    echo "check.sh: skipped: scripts/smoke_viewer.sh is missing"
fi
echo "== sharded render on a local one-node Slurm cluster"
scripts/slurm/test-local.sh
echo "== check.sh: all checks passed"
