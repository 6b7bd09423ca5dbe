#!/usr/bin/env bash
# The validation report opens in a real browser: Debian's chromium renders report.html
# headless to a PNG; the page must load without console errors, hold every section, and
# the picture must show the plot colours.
set -euo pipefail
TRIBO=target/release/tribo
OUT=target/ci-report
rm -rf "$OUT" && mkdir -p "$OUT"
if ! command -v chromium >/dev/null; then
  apt-get update -qq && apt-get install -y -qq chromium >/dev/null
fi
python3 -c "import PIL" 2>/dev/null || python3 -m pip install --quiet pillow
echo "== refinement study (3 levels, quadratic mortar) and validate --report"
"$TRIBO" study hertz --levels 3 --kinematics small --report "$OUT" > "$OUT/study.txt"
t0=$(date +%s%N)
"$TRIBO" validate --report "$OUT" > "$OUT/validate.txt"
t1=$(date +%s%N)
echo "  validate --report (all modelisations, built-in meshes): $(( (t1 - t0) / 1000000 )) ms"
FLAGS="--headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync \
  --user-data-dir=$PWD/$OUT/chromium-profile"
# shellcheck disable=SC2086
chromium $FLAGS --enable-logging=stderr --v=0 --window-size=1200,9000 \
  --screenshot="$PWD/$OUT/report.png" "file://$PWD/$OUT/report.html" 2> "$OUT/chromium.log" || {
  cat "$OUT/chromium.log"; exit 1; }
# shellcheck disable=SC2086
chromium $FLAGS --dump-dom "file://$PWD/$OUT/report.html" > "$OUT/dom.html" 2>> "$OUT/chromium.log"
# Layout at 1280 px: a copy of the page with .ci/layout_check.js at its end measures what
# the browser laid out (horizontal scroll, boxes overflowing, SVG text cut by its picture
# or drawn over other text, markers under a legend, over-long numbers) into the DOM.
bash .ci/check_layout.sh "$OUT/report.html" "$OUT" 2>> "$OUT/chromium.log"
if grep -E "CONSOLE|Uncaught|Failed to load" "$OUT/chromium.log"; then
  echo "FAILED: the browser reported errors"; exit 1
fi
python3 - "$OUT" <<'PY'
import sys
from PIL import Image
out = sys.argv[1]
dom = open(f"{out}/dom.html").read()
need = ["<table>", "contact pressure", "shear traction", "deformed contact region",
        "Newton convergence", "Refinement study", "refinement: mortar quadratic small",
        "Versions and settings"]
missing = [n for n in need if n not in dom]
if missing:
    print("FAILED: the rendered page lacks", missing); sys.exit(1)
img = Image.open(f"{out}/report.png").convert("RGB")
w, h = img.size
px = img.getdata()
colors = {"Hertz blue": (0x1f, 0x77, 0xb4), "multiplier red": (0xd6, 0x27, 0x28),
          "stress green": (0x2c, 0xa0, 0x2c)}
counts = {k: 0 for k in colors}
nonwhite = 0
for p in px:
    if p != (255, 255, 255):
        nonwhite += 1
    for k, c in colors.items():
        if all(abs(p[i] - c[i]) <= 12 for i in range(3)):
            counts[k] += 1
print(f"  report.png {w}x{h}: {nonwhite} non-white pixels, plot colours {counts}")
if nonwhite < 0.02 * w * h or min(counts.values()) < 200:
    print("FAILED: the rendered report looks blank"); sys.exit(1)
PY
