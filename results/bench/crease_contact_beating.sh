#!/usr/bin/env bash
# The crease contact on a beating wall (engine/contact/detect_contacts.hpp kCreaseDepthMm; docs/physics.md "A tip
# wedged in a crease"): bench-mechanics --heart-rate 60 (the generator's coronary field) on the jam (validation-pool
# tree coronary_900001_0032) and on pl_validation, this build and, with OLD=a bench-mechanics built before the crease
# contact, that one, in turn: the beating insertion's halvings, contact solves, deepest penetration, hash and time per
# sub-step. Writes results/bench/crease_contact_beating.json. Run from the repository root after
# `bash scripts/install.sh`:
#   OLD=/path/to/old/bench-mechanics bash results/bench/crease_contact_beating.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
POOL=runs/pool/validation
.venv/bin/gw-anatomy-pool --out "$POOL" --count 40 --seed 900001 --jobs 2 > /dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A anatomy=([jam]="$POOL/coronary/coronary_900001_0032/coronary_900001_0032"
                    [pl_validation]=anatomies/validation/pl_validation/pl_validation)
for case in jam pl_validation; do
  build/apps/bench-mechanics --anatomy "${anatomy[$case]}" --scaling-substeps 1 --heart-rate 60 > "$tmp/${case}_new.json"
  if [ -n "${OLD:-}" ]; then
    "$OLD" --anatomy "${anatomy[$case]}" --scaling-substeps 1 --heart-rate 60 > "$tmp/${case}_old.json"
  fi
done
.venv/bin/python - "$tmp" results/bench/crease_contact_beating.json <<'PY'
import datetime, json, pathlib, subprocess, sys
tmp, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
keys = ["substeps", "split_substeps", "contact_solves", "max_penetration_mm", "trajectory_hash", "ok"]
result = {"what": "bench-mechanics --scaling-substeps 1 --heart-rate 60: the beating insertion with the crease contact "
                  "(new) and before it (old) (results/bench/crease_contact_beating.sh)",
          "commit": commit, "date": datetime.date.today().isoformat()}
for case in ["jam", "pl_validation"]:
    entry = {}
    for build in ["new", "old"]:
        path = tmp / f"{case}_{build}.json"
        if not path.exists():
            continue
        run = json.loads(path.read_text())["beating"]["insertion"]
        entry[build] = {k: run[k] for k in keys}
        entry[build]["us_per_substep"] = round(1e6 / run["substeps_per_s"], 1)
    if "old" in entry:
        entry["ratio_old_over_new_per_substep"] = round(entry["old"]["us_per_substep"] / entry["new"]["us_per_substep"], 3)
    result[case] = entry
out.write_text(json.dumps(result, indent=1) + "\n")
print("wrote", out)
PY
