#!/usr/bin/env bash
# The headless build (raygine without its `viewer` feature) must have no GUI, window-system or
# OpenGL crate in its dependency tree: cluster nodes build and run it without a display.
# Exit 1 naming the crates (and the path that pulls them in) if one appears. scripts/check.sh
# runs it; it reads Cargo.lock and builds nothing.
set -euo pipefail
cd "$(dirname "$0")/.."

gui='^(eframe|egui.*|epaint.*|emath|ecolor|rfd|glow|glutin.*|winit|wayland-.*|x11.*|xkb.*|smithay-.*|accesskit.*|ashpd|zbus|gtk.*|gdk.*|raw-window-handle|glutin_.*|khronos-egl|calloop.*|sctk.*|objc2.*|windows-sys|web-sys)$'
crates=$(cargo tree -p raygine --no-default-features -e normal,build --prefix none --locked |
    sed 's/ v[0-9].*//' | sort -u)
found=$(grep -E "$gui" <<<"$crates" || true)
if [ -n "$found" ]; then
    echo "check_headless.sh: FAILED: the headless build depends on GUI crates:" >&2
    for c in $found; do
        echo "--- $c, pulled in by:" >&2
        cargo tree -p raygine --no-default-features -e normal,build -i "$c" --locked >&2 || true
    done
    exit 1
fi
echo "check_headless.sh: the headless build has $(wc -l <<<"$crates") crates, none of them GUI, window or OpenGL"
