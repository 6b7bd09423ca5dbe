#!/usr/bin/env bash
# check_layout.sh PAGE.html WORKDIR: renders PAGE in headless Chromium at 1280 px width with
# .ci/layout_check.js appended and fails (exit 1) on horizontal scroll, a box whose content
# overflows it, SVG text cut by the edge of its picture or drawn over other text, data
# markers under a legend entry, or a number printed with 7 or more decimals.
# (`bash .ci/check_layout.sh OLD/report.html /tmp/x` shows it failing on a page that has them.)
set -euo pipefail
PAGE=$1
WORK=$2
HERE="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$WORK"
python3 - "$PAGE" "$HERE/layout_check.js" "$WORK/layout.html" <<'PY'
import sys
page, js, out = sys.argv[1:4]
html = open(page, encoding="utf-8").read()
script = "<script>" + open(js, encoding="utf-8").read() + "</script>"
open(out, "w", encoding="utf-8").write(html.replace("</body>", script + "</body>"))
PY
# (the copy sits beside the page's own files: same relative links)
cp "$WORK/layout.html" "$(dirname "$PAGE")/.layout-check.html"
chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync \
  --user-data-dir="$WORK/chromium-layout-profile" --window-size=1280,900 \
  --dump-dom "file://$(cd "$(dirname "$PAGE")" && pwd)/.layout-check.html" > "$WORK/layout-dom.html"
rm -f "$(dirname "$PAGE")/.layout-check.html"
python3 - "$WORK/layout-dom.html" <<'PY'
import html, json, re, sys
dom = open(sys.argv[1], encoding="utf-8").read()
found = re.findall(r'<pre id="layout-check">(\{.*?\})</pre>', dom, re.S)
if not found:
    print("FAILED: the layout check did not run in the browser"); sys.exit(1)
r = json.loads(html.unescape(found[-1]))
if r["innerWidth"] != 1280:
    print(f"FAILED: the page was laid out {r['innerWidth']} px wide, not 1280"); sys.exit(1)
problems = []
if r["scrollWidth"] > r["innerWidth"]:
    problems.append(f"horizontal scroll: the page is {r['scrollWidth']} px wide in a 1280 px window")
for key, what in [("outside", "past the right edge of the page"),
                  ("overflowing", "content wider than its box"),
                  ("clipped", "text cut by the edge of its picture"),
                  ("overlapping", "texts drawn over each other"),
                  ("covered", "data markers under a legend entry"),
                  ("long_numbers", "numbers with 7 or more decimals")]:
    if r[key]:
        problems.append(f"{what} ({len(r[key])}): " + "; ".join(r[key][:5]))
print(f"  layout at 1280 px: page {r['scrollWidth']} px wide; "
      + ("no clipped or overlapping text" if not problems else f"{len(problems)} problems"))
for p in problems:
    print("FAILED:", p)
sys.exit(1 if problems else 0)
PY
