#!/usr/bin/env bash
# MED and MSH reference meshes read the same; conversions and results checked with an
# independent reader (meshio + h5py, installed here from PyPI).
set -euo pipefail
SHARED="$1"
TRIBO=target/release/tribo
OUT=target/ci-formats
rm -rf "$OUT" && mkdir -p "$OUT"
python3 -c "import meshio, h5py" 2>/dev/null || python3 -m pip install --quiet meshio h5py
for m in a b; do
  echo "== ssnp154$m: MED against MSH (tribo mesh compare)"
  "$TRIBO" mesh compare "$SHARED/ssnp154$m.mmed" "$SHARED/ssnp154$m.msh"
  "$TRIBO" mesh convert "$SHARED/ssnp154$m.mmed" "$OUT/$m-from-med.vtu"
  "$TRIBO" mesh convert "$SHARED/ssnp154$m.msh" "$OUT/$m-from-msh.med"
  "$TRIBO" mesh convert "$SHARED/ssnp154$m.msh" "$OUT/$m.msh22" --format msh22
  "$TRIBO" mesh convert "$OUT/$m-from-msh.med" "$OUT/$m-rt.msh"
  echo "== ssnp154$m: round trips MSH -> MED -> MSH and MSH 2.2"
  "$TRIBO" mesh compare "$SHARED/ssnp154$m.msh" "$OUT/$m-rt.msh"
  "$TRIBO" mesh compare "$SHARED/ssnp154$m.msh" "$OUT/$m.msh22"
  echo "== ssnp154$m: independent reader (meshio)"
  python3 .ci/check_formats.py mesh "$SHARED/ssnp154$m.mmed" "$OUT/$m-from-med.vtu" \
    "$OUT/$m-from-msh.med" "$SHARED/ssnp154$m.msh"
done
echo "== results of a frictional run read back with meshio"
"$TRIBO" run cases/ssnp154/c.toml -o "$OUT/run-c" > /dev/null
python3 .ci/check_formats.py result "$OUT/run-c"
echo "== validate on the MED reference meshes gives the numbers of the MSH ones"
"$TRIBO" validate --meshes "$SHARED" --mesh-format med --json "$OUT/validate-med.json" > "$OUT/validate-med.txt" || {
  cat "$OUT/validate-med.txt"; exit 1; }
python3 - target/validate-reference.json "$OUT/validate-med.json" <<'PY'
import json, sys
a, b = (json.load(open(f))["cases"] for f in sys.argv[1:3])
diffs = [(x["id"], q) for x, y in zip(a, b) for q in ("DY_B", "SIYY_B")
         if x["id"] != y["id"] or x[q]["value"] != y[q]["value"]]
if len(a) != len(b) or diffs:
    print("FAILED: MED and MSH runs differ:", diffs); sys.exit(1)
print(f"  {len(a)} modelisations: DY_B and SIYY_B identical from the MED and the MSH meshes")
PY
