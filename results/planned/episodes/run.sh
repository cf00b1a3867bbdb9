#!/bin/bash
# Every episode of the table's rows planned from its own start (evaluate --planned-seeds episodes: the anatomy,
# target and seed the columns' controllers had), with the shipped actor and the scripted rule on the same episodes,
# half the table's episode counts; then every target of the three test arches with the aortic wire, planned from up
# to two seeds each (an anatomy index row: the arches' meshes made here by anatomy-gen). Resumable: a row
# results.json already holds is kept (--resume). Two threads; about 25 min for the first six rows on 2 cores.
#   bash results/planned/episodes/run.sh                 # every row of the table, then the arches
#   ROWS="coronary-like" bash results/planned/episodes/run.sh   # some rows only (evaluate --rows)
set -euo pipefail
cd "$(dirname "$0")/../../.."
BUILD=${GW_BUILD_DIR:-build}
OUT=${OUT:-results/planned/episodes}
ARCHES=${ARCHES:-runs/test_arches}
common=(--controllers policy,scripted-omega --reachability-seeds 0 --plan-budget 5000 --threads "${THREADS:-2}")

"$BUILD/apps/evaluate" ${ROWS:+--rows "$ROWS"} --episode-scale 0.5 --planned-seeds episodes "${common[@]}" \
    --out "$OUT" --resume

mkdir -p "$ARCHES"
for k in 1 2 3; do
  [ -f "$ARCHES/arch_type$k.stl" ] || "$BUILD/apps/anatomy-gen" --spec anatomies/segmentation/arch_type$k.spec.json \
      --out "$ARCHES" > /dev/null
done
mkdir -p "$ARCHES/wires" && cp engine/wire/aortic_035_angled.json "$ARCHES/wires/"
python3 - "$ARCHES" <<'PY'
import json, pathlib, sys
out = pathlib.Path(sys.argv[1])  # an index's paths are relative to its folder's parent, as gw-anatomy-pool's
rows = [{"name": f"arch_type{k}", "set": "arch", "mesh": f"{out.name}/arch_type{k}.stl",
         "truth": f"{out.name}/arch_type{k}.truth.json", "wire": f"{out.name}/wires/aortic_035_angled.json"}
        for k in (1, 2, 3)]
(out / "index.json").write_text(json.dumps({"anatomies": rows}, indent=1) + "\n")
PY
"$BUILD/apps/evaluate" --rows "$ARCHES/index.json" --planned-seeds 2 "${common[@]}" --out "$OUT/arches" --resume
