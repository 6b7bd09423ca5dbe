#!/usr/bin/env bash
# Reads the SSNP154 reference meshes with `tribo mesh info --json` and checks the counts and
# groups stated in ../shared/ssnp154/README.md; then runs the elastic stage on them.
set -euo pipefail
SHARED="$1"
TRIBO=target/release/tribo
check() {
  local file="$1" expect="$2"
  local t0 t1
  t0=$(date +%s%N)
  "$TRIBO" mesh info --json "$SHARED/$file" > "target/$file.json"
  t1=$(date +%s%N)
  echo "$file: mesh info in $(( (t1 - t0) / 1000000 )) ms"
  python3 - "target/$file.json" "$expect" <<'PY'
import json, sys
got = json.load(open(sys.argv[1]))
exp = json.loads(sys.argv[2])
errors = []
if got["nodes"] != exp["nodes"]:
    errors.append(f"nodes {got['nodes']} != {exp['nodes']}")
for kind, n in exp["cells"].items():
    if got["cells"].get(kind) != n:
        errors.append(f"{kind} cells {got['cells'].get(kind)} != {n}")
for g, dim in exp["groups"].items():
    if g not in got["groups"]:
        errors.append(f"group {g} missing")
    elif got["groups"][g]["dim"] != dim:
        errors.append(f"group {g} dim {got['groups'][g]['dim']} != {dim}")
for g in ["B", "C", "Force"]:
    if g in got["groups"] and got["groups"][g]["nodes"] != 1:
        errors.append(f"group {g} has {got['groups'][g]['nodes']} nodes, expected 1")
if errors:
    print("FAILED:", "; ".join(errors)); sys.exit(1)
print("  counts and groups as in the README:", {k: got["cells"][k] for k in exp["cells"]}, "reoriented", got["reoriented"])
PY
}
GRP='"Block": 2, "Cylinder": 2, "Top_B": 1, "Bottom_C": 1, "Axe": 1, "Encast": 1, "B": 0, "C": 0, "Force": 0'
check ssnp154a.msh "{\"nodes\": 2625, \"cells\": {\"Quad4\": 2467, \"Tri3\": 53}, \"groups\": {$GRP}}"
check ssnp154b.msh "{\"nodes\": 7768, \"cells\": {\"Quad8\": 2467, \"Tri6\": 53}, \"groups\": {$GRP}}"

echo "== SSNP154 validation on the reference meshes"
"$TRIBO" validate --meshes "$SHARED" --json target/validate-reference.json
echo "== SSNP154 with the mortar formulation on the reference meshes"
"$TRIBO" validate --meshes "$SHARED" --formulation mortar --json target/validate-reference-mortar.json
