#!/usr/bin/env bash
# Smoke run of the raygine viewer in a real X11 window (Xvfb, software OpenGL):
#   1. the window opens and shows the built-in Cornell box: red wall left, green wall right;
#   2. an xdotool drag on the first "light x" slider changes the picture;
#   3. the app is still running, then the script ends it;
#   4. when ../shared is present, the viewer opens the Integra room ipur-room2 from the command
#      line and its viewport (seen from room2.cam) is lit; the script ends it and exits.
# Screenshots and the app's log go to target/smoke/. Exit 0 on success; 1 with a message on
# failure; 0 with "SKIP:" when the X tools are missing and cannot be installed (SMOKE_STRICT=1
# or CI=true turns that into a failure, and so does an absent room2 under CI=true).
#
# Environment: SMOKE_PROFILE=release uses a release build (default: debug).
set -euo pipefail

cd "$(dirname "$0")/.."
ROOT=$(pwd)
OUT="$ROOT/target/smoke"
SCREEN_W=1600
SCREEN_H=1000

fail() {
    echo "smoke: FAIL: $*" >&2
    exit 1
}

# ---------------------------------------------------------------------------------------------
# Inside Xvfb: drive the app. Called by the outer part below through xvfb-run.
# ---------------------------------------------------------------------------------------------
if [[ "${1:-}" == "--inside-xvfb" ]]; then
    BIN=$2

    # Mean colour "R G B" (0..255) of a region of a screenshot.
    mean_rgb() { # file w h x y
        convert "$1" -crop "$2x$3+$4+$5" +repage -scale '1x1!' \
            -format '%[fx:int(255*r+0.5)] %[fx:int(255*g+0.5)] %[fx:int(255*b+0.5)]\n' info:
    }
    shot() { # name
        import -window root "$OUT/$1.png"
    }

    # A private home: no persisted preferences or last scene leak in, none leak out.
    PRIVATE=$(mktemp -d)
    mkdir -p "$PRIVATE/home" "$PRIVATE/data" "$PRIVATE/config" "$PRIVATE/runtime"
    chmod 700 "$PRIVATE/runtime"
    APP_PID=""
    cleanup() {
        if [[ -n "$APP_PID" ]] && kill -0 "$APP_PID" 2>/dev/null; then
            kill -TERM "$APP_PID" 2>/dev/null || true
            for _ in 1 2 3 4 5 6 7 8 9 10; do
                kill -0 "$APP_PID" 2>/dev/null || break
                sleep 0.5
            done
            kill -KILL "$APP_PID" 2>/dev/null || true
        fi
        rm -rf "$PRIVATE"
    }
    trap cleanup EXIT

    env -u WAYLAND_DISPLAY \
        HOME="$PRIVATE/home" XDG_DATA_HOME="$PRIVATE/data" XDG_CONFIG_HOME="$PRIVATE/config" \
        XDG_RUNTIME_DIR="$PRIVATE/runtime" RAYGINE_FRAME_STATS=1 \
        "$BIN" --no-restore >"$OUT/raygine.log" 2>&1 &
    APP_PID=$!

    WID=$(timeout 60 xdotool search --sync --name '^raygine$' | head -n 1) ||
        fail "no raygine window within 60 s (log: $OUT/raygine.log)"
    [[ -n "$WID" ]] || fail "no raygine window (log: $OUT/raygine.log)"
    eval "$(xdotool getwindowgeometry --shell "$WID")" # X Y WIDTH HEIGHT
    echo "smoke: window $WID at ${X},${Y} size ${WIDTH}x${HEIGHT}"

    # Layout of the window (egui, 1 point = 1 pixel under Xvfb): menu bar on top, status bar at
    # the bottom, the side panel (378 points wide at this size) on the left, the viewport to its right.
    # The Cornell box fills the viewport's middle; at the default camera its left (red) wall spans
    # about 14-28 % of the viewport's width at mid-height, the right (green) wall 72-86 %.
    PANEL_W=378
    BAR_H=25
    VX=$((X + PANEL_W))
    VY=$((Y + BAR_H))
    VW=$((WIDTH - PANEL_W))
    VH=$((HEIGHT - 2 * BAR_H))
    SAMPLE_W=$((VW / 40))
    SAMPLE_H=$((VH / 10))
    LEFT_X=$((VX + VW * 21 / 100 - SAMPLE_W / 2))
    RIGHT_X=$((VX + VW * 79 / 100 - SAMPLE_W / 2))
    MID_Y=$((VY + VH / 2 - SAMPLE_H / 2))

    # Keep the pointer off the viewport: hovering there draws a read-out over the picture.
    xdotool mousemove $((X + 150)) $((Y + HEIGHT - 60))

    # Wait for the picture: up to 60 s for red on the left and green on the right.
    ok=""
    for attempt in $(seq 1 30); do
        sleep 2
        kill -0 "$APP_PID" 2>/dev/null || fail "the app exited (log: $OUT/raygine.log)"
        shot 01-cornell
        read -r lr lg lb < <(mean_rgb "$OUT/01-cornell.png" "$SAMPLE_W" "$SAMPLE_H" "$LEFT_X" "$MID_Y")
        read -r rr rg rb < <(mean_rgb "$OUT/01-cornell.png" "$SAMPLE_W" "$SAMPLE_H" "$RIGHT_X" "$MID_Y")
        echo "smoke: attempt $attempt: left wall rgb($lr,$lg,$lb), right wall rgb($rr,$rg,$rb)"
        # Filmic tone mapping desaturates the lit walls (red is about rgb(229,97,80) at the
        # default exposure): ask for a clear lead of the wall's colour, not a ratio.
        if ((lr > lg + 60 && lr > lb + 60 && rg > rr + 40 && rg > rb + 40)); then
            ok=1
            break
        fi
    done
    [[ -n "$ok" ]] || fail "expected a red left wall and a green right wall (see $OUT/01-cornell.png)"
    # Let the render converge so the comparison below sees the slider's change, not noise.
    sleep 3
    shot 02-before-drag

    # The first light's "x" position field: its centre, measured in the egui layout at this
    # window size (the test `smoke_script_layout_holds` keeps it true). Drag it left by 40 px:
    # the light moves about 55 mm (1.4 mm a point in the box) and stays inside the box.
    SLIDER_X=$((X + 138))
    SLIDER_Y=$((Y + 175))
    xdotool mousemove "$SLIDER_X" "$SLIDER_Y" mousedown 1
    for dx in 10 20 30 40; do
        sleep 0.1
        xdotool mousemove $((SLIDER_X - dx)) "$SLIDER_Y"
    done
    xdotool mouseup 1
    # Frames take a few hundred ms in a debug build on software GL: give the release a frame of
    # its own, or egui applies the next pointer move to the slider too.
    sleep 1.5
    xdotool mousemove $((X + 150)) $((Y + HEIGHT - 60))
    sleep 5
    kill -0 "$APP_PID" 2>/dev/null || fail "the app exited after the drag (log: $OUT/raygine.log)"
    shot 03-after-drag
    read -r lr lg lb < <(mean_rgb "$OUT/03-after-drag.png" "$SAMPLE_W" "$SAMPLE_H" "$LEFT_X" "$MID_Y")
    echo "smoke: after the drag: left wall rgb($lr,$lg,$lb)"
    ((lr > lg + 30 && lr > lb + 30)) || fail "the light left the box: no lit red wall (see $OUT/03-after-drag.png)"

    crop() { # in out
        convert "$1" -crop "${VW}x${VH}+${VX}+${VY}" +repage "$2"
    }
    crop "$OUT/02-before-drag.png" "$OUT/viewport-before.png"
    crop "$OUT/03-after-drag.png" "$OUT/viewport-after.png"
    changed=$(compare -metric AE -fuzz 4% "$OUT/viewport-before.png" "$OUT/viewport-after.png" null: 2>&1 || true)
    changed=${changed%%.*}
    [[ "$changed" =~ ^[0-9]+$ ]] || fail "cannot compare the screenshots: $changed"
    total=$((VW * VH))
    echo "smoke: the drag changed $changed of $total viewport pixels"
    ((changed * 50 > total)) || fail "the slider drag did not change the picture (see $OUT/03-after-drag.png)"

    grep -E '^frame-stats' "$OUT/raygine.log" | tail -n 1 || true

    # 4. The Integra room (../shared, when present) opens with its own camera and nine lamps:
    # the lower part of the viewport (floor, rug, chairs, walls under the lamps) must be lit.
    ROOM2="${RAYGINE_SHARED:-$ROOT/../shared}/scenes/ipur-room2/room2.shp"
    if [[ -f "$ROOM2" ]]; then
        kill -TERM "$APP_PID" 2>/dev/null || true
        for _ in $(seq 1 20); do
            kill -0 "$APP_PID" 2>/dev/null || break
            sleep 0.5
        done
        env -u WAYLAND_DISPLAY \
            HOME="$PRIVATE/home" XDG_DATA_HOME="$PRIVATE/data" XDG_CONFIG_HOME="$PRIVATE/config" \
            XDG_RUNTIME_DIR="$PRIVATE/runtime" \
            "$BIN" --no-restore "$ROOM2" >"$OUT/raygine-room2.log" 2>&1 &
        APP_PID=$!
        WID=$(timeout 60 xdotool search --sync --name '^raygine$' | head -n 1) ||
            fail "no raygine window for room2 within 60 s (log: $OUT/raygine-room2.log)"
        eval "$(xdotool getwindowgeometry --shell "$WID")"
        xdotool mousemove $((X + 150)) $((Y + HEIGHT - 60))
        BAND_Y=$((Y + BAR_H + (HEIGHT - 2 * BAR_H) * 55 / 100))
        BAND_H=$(((HEIGHT - 2 * BAR_H) * 30 / 100))
        lit=""
        for attempt in $(seq 1 30); do
            sleep 2
            kill -0 "$APP_PID" 2>/dev/null || fail "the app exited on room2 (log: $OUT/raygine-room2.log)"
            shot 04-room2
            read -r r g b < <(mean_rgb "$OUT/04-room2.png" "$VW" "$BAND_H" "$VX" "$BAND_Y")
            echo "smoke: room2 attempt $attempt: lower viewport rgb($r,$g,$b)"
            if (((r + g + b) / 3 > 25)); then
                lit=1
                break
            fi
        done
        [[ -n "$lit" ]] || fail "room2's viewport is not lit (see $OUT/04-room2.png)"
    else
        [[ "${CI:-}" == "true" ]] && fail "$ROOM2 is absent, and CI=true requires ../shared"
        echo "smoke: room2 skipped: $ROOM2 is absent"
    fi
    echo "smoke: OK"
    exit 0
fi

# ---------------------------------------------------------------------------------------------
# Outside: tools, build, then run the inner part under Xvfb.
# ---------------------------------------------------------------------------------------------
skip() {
    if [[ "${SMOKE_STRICT:-0}" == "1" || "${CI:-}" == "true" ]]; then
        fail "$*"
    fi
    echo "smoke: SKIP: $*"
    exit 0
}

TOOLS=(xvfb-run xauth xdotool import convert compare)
missing=()
for t in "${TOOLS[@]}"; do
    command -v "$t" >/dev/null || missing+=("$t")
done
if ((${#missing[@]})); then
    if [[ $(id -u) == 0 ]] && command -v apt-get >/dev/null; then
        echo "smoke: installing X tools (missing: ${missing[*]})"
        DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
            xvfb xauth x11-apps xdotool imagemagick libgl1-mesa-dri libegl-mesa0 ||
            skip "cannot install the X tools (missing: ${missing[*]})"
    else
        skip "missing ${missing[*]} and not root with apt-get to install them"
    fi
fi

mkdir -p "$OUT"
rm -f "$OUT"/*.png "$OUT/raygine.log"
if [[ "${SMOKE_PROFILE:-debug}" == "release" ]]; then
    cargo build --release -p raygine
    BIN="$ROOT/target/release/raygine"
else
    cargo build -p raygine
    BIN="$ROOT/target/debug/raygine"
fi
[[ -x "$BIN" ]] || fail "no binary at $BIN"

timeout 260 xvfb-run -a -s "-screen 0 ${SCREEN_W}x${SCREEN_H}x24" \
    bash "$0" --inside-xvfb "$BIN" || fail "the run under Xvfb failed or timed out (see above)"
