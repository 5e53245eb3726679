#!/usr/bin/env bash
# Installs Intel Open Image Denoise 2.x (the `pyoidn` wheel from PyPI, which carries the
# library in its lib folder) into a virtual environment outside the repository, once, and
# prints that lib folder: `RAYGINE_OIDN=$(scripts/oidn.sh) cargo run --release`.
# raygine builds and runs without it (the denoiser is then off, with the reason shown).
# The environment: $RAYGINE_OIDN_VENV, default ~/.cache/raygine/oidn-venv.
set -euo pipefail
VENV="${RAYGINE_OIDN_VENV:-${XDG_CACHE_HOME:-$HOME/.cache}/raygine/oidn-venv}"
PY="${PYTHON:-python3}"
find_lib() {
    find "$VENV" -path '*/pyoidn/oidn/lib/libOpenImageDenoise.so.2' -print -quit 2>/dev/null
}
lib=$(find_lib || true)
if [ -z "$lib" ]; then
    echo "oidn.sh: installing pyoidn (Open Image Denoise) into $VENV" >&2
    command -v "$PY" >/dev/null 2>&1 || { echo "oidn.sh: $PY not found" >&2; exit 1; }
    mkdir -p "$(dirname "$VENV")"
    "$PY" -m venv "$VENV" >&2
    "$VENV/bin/pip" install --quiet --disable-pip-version-check 'pyoidn>=2.0,<3' >&2
    lib=$(find_lib || true)
fi
[ -n "$lib" ] || { echo "oidn.sh: no libOpenImageDenoise.so.2 in $VENV" >&2; exit 1; }
dirname "$lib"
