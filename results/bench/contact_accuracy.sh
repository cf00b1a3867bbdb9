#!/usr/bin/env bash
# How accurate the contact forces are (issue 62 item 1, issue 64 item 3): bench-mechanics --contact-accuracy on four
# insertions (20 mm/s, 100 mm, no rotation), every 10th sub-step's contact problem also solved to convergence on a copy.
# The coronary test tree (the speed benchmark's), a training pattern, the validation tree pl_validation, and a
# validation-pool tree with 0.3-0.5 mm distal vessels where the wire jams (coronary_900001_0032: drawn by
# gw-anatomy-pool, seed 900001, never a test row). Each benchmark's own JSON, with the commit. Run from the
# repository root after `bash scripts/install.sh` (about 10 min on one core):   bash results/bench/contact_accuracy.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
B=build/apps
POOL=${POOL:-runs/pool/validation}
out=results/bench/contact_accuracy.json
.venv/bin/gw-anatomy-pool --out "$POOL" --count 40 --seed 900001 --jobs 2 > /dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A stems=(
  [coronary]=anatomies/test/coronary/coronary
  [t3_out_of_plane_steep]=anatomies/train/t3_out_of_plane_steep/t3_out_of_plane_steep
  [pl_validation]=anatomies/validation/pl_validation/pl_validation
  [pool_coronary_900001_0032]=$POOL/coronary/coronary_900001_0032/coronary_900001_0032
)
for name in coronary t3_out_of_plane_steep pl_validation pool_coronary_900001_0032; do
  $B/bench-mechanics --anatomy "${stems[$name]}" --scaling-substeps 1 --contact-accuracy 10 > "$tmp/$name.json"
done
.venv/bin/python - "$tmp" "$out" <<'PY'
import json, pathlib, subprocess, sys, datetime
tmp, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
record = {"what": "contact force accuracy of the capped projected Gauss-Seidel solve (results/bench/contact_accuracy.sh): "
                  "bench-mechanics --contact-accuracy 10 --scaling-substeps 1 on each anatomy; errors are relative "
                  "(engine/contact/contact_force_error.hpp), quantiles over the checked sub-steps",
          "commit": commit, "date": datetime.date.today().isoformat(), "runs": {}}
for f in sorted(tmp.glob("*.json")):
    d = json.loads(f.read_text())
    d.pop("scaling_free_space", None)  # one timed sub-step per node count: not a figure
    record["runs"][f.stem] = d
out.write_text(json.dumps(record, indent=2) + "\n")
PY
echo "wrote $out"
