#!/usr/bin/env bash
# Why a jammed wire simulates slowly (issue 62; docs/physics.md "How accurate the contact forces are"): is it the
# capped contact solve? bench-mechanics's insertion (20 mm/s, 100 mm, no rotation) into the validation-pool tree
# where the wire jams in 0.3-0.5 mm distal vessels (coronary_900001_0032: gw-anatomy-pool seed 900001, never a test
# row), with the shipped 0.014" wire at its 100 projected Gauss-Seidel sweeps per solve and at 400. The halvings of
# the sub-step (split_substeps) and the solves are counts, the same on any machine; the timings are this machine's.
# Run from the repository root after `bash scripts/install.sh` (about 10 min on one core):
#   bash results/bench/jam_sweeps.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
POOL=${POOL:-runs/pool/validation}
out=results/bench/jam_sweeps.json
.venv/bin/gw-anatomy-pool --out "$POOL" --count 40 --seed 900001 --jobs 2 > /dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for sweeps in 100 400; do
  .venv/bin/python -c 'import json, sys; p = json.load(open(sys.argv[1])); p["contact_iterations"] = int(sys.argv[2]);
json.dump(p, open(sys.argv[3], "w"), indent=1)' engine/wire/coronary_014.json "$sweeps" "$tmp/wire_$sweeps.json"
  build/apps/bench-mechanics --anatomy "$POOL/coronary/coronary_900001_0032/coronary_900001_0032" \
    --scaling-substeps 1 --params "$tmp/wire_$sweeps.json" > "$tmp/sweeps_$sweeps.json"
done
.venv/bin/python - "$tmp" "$out" <<'PY'
import datetime, json, pathlib, subprocess, sys
tmp, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
keys = ["substeps", "split_substeps", "contact_solves", "share_contact_solves_at_sweep_cap", "mean_max_pgs_sweeps",
        "substeps_per_s", "us_per_substep_by_stage", "trajectory_hash", "ok"]
runs = {}
for sweeps in (100, 400):
    insertion = json.loads((tmp / f"sweeps_{sweeps}.json").read_text())["insertion"]
    runs[f"contact_iterations_{sweeps}"] = {k: insertion[k] for k in keys}
record = {"what": "bench-mechanics --scaling-substeps 1 on validation-pool tree coronary_900001_0032 (a jam), the shipped "
                  "0.014 inch wire with contact_iterations 100 (shipped) and 400 (results/bench/jam_sweeps.sh)",
          "commit": commit, "date": datetime.date.today().isoformat(), "runs": runs}
out.write_text(json.dumps(record, indent=1) + "\n")
print(json.dumps({k: {"split_substeps": v["split_substeps"], "substeps_per_s": round(v["substeps_per_s"])}
                  for k, v in runs.items()}))
PY
