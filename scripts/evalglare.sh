#!/usr/bin/env bash
# Installs Radiance's evalglare (the `pyradiance` wheel from PyPI, which carries Radiance's
# programs in its bin folder) into a virtual environment outside the repository, once, and
# prints its path: `RAYGINE_EVALGLARE=$(scripts/evalglare.sh) cargo test glare_evalglare`.
# The glare tests compare raygine's UGR and DGP with it; without it they skip with the reason.
# The environment: $RAYGINE_RADIANCE_VENV, default ~/.cache/raygine/radiance-venv.
set -euo pipefail
VENV="${RAYGINE_RADIANCE_VENV:-${XDG_CACHE_HOME:-$HOME/.cache}/raygine/radiance-venv}"
PY="${PYTHON:-python3}"
find_exe() {
    find "$VENV" -path '*/pyradiance/bin/evalglare' -type f -print -quit 2>/dev/null
}
exe=$(find_exe || true)
if [ -z "$exe" ]; then
    echo "evalglare.sh: installing pyradiance (Radiance, evalglare 3.06) into $VENV" >&2
    command -v "$PY" >/dev/null 2>&1 || { echo "evalglare.sh: $PY not found" >&2; exit 1; }
    mkdir -p "$(dirname "$VENV")"
    "$PY" -m venv "$VENV" >&2
    "$VENV/bin/pip" install --quiet --disable-pip-version-check 'pyradiance==1.3.1' >&2
    exe=$(find_exe || true)
fi
[ -n "$exe" ] || { echo "evalglare.sh: no evalglare in $VENV" >&2; exit 1; }
echo "$exe"
