#!/usr/bin/env bash
# The planner with controller guides (issue 63; docs/planning.md "Guides first") on validation anatomies only:
# three beating coronary trees drawn for it (gw-anatomy-pool seed 900003, never a test row, never trained on), every
# target planned from seed 0 at 60 bpm with a budget of 5,000 env steps, and the shipped actor and the scripted rule
# run once per target (seed 0, their own task) for comparison; and the static validation tree rca_validation,
# every target planned. Writes the JSON files of this folder. Run from the repository root after
# `bash scripts/install.sh`:  bash results/planned/guides/run.sh
set -euo pipefail
cd "$(dirname "$0")/../../.."
out=results/planned/guides
pool=runs/pool/validation_beating
.venv/bin/gw-anatomy-pool --out "$pool" --count 3 --seed 900003 --kinds coronary --beating --jobs 1 > /dev/null
for k in 0 1 2; do
  a=$pool/coronary/coronary_900003_000$k/coronary_900003_000$k.stl
  n=$(build/apps/navigate --anatomy "$a" --list 2> /dev/null | grep -cE "^ +[0-9]+ ")
  for t in $(seq 1 "$n"); do
    build/apps/plan --anatomy "$a" --target "$t" --budget 5000 --heart-rate 60 --json > "$out/vbeat${k}_hr60_t$t.json" || true
  done
  for c in policy scripted-omega; do
    build/apps/navigate --anatomy "$a" --heart-rate 60 --target all --episodes 1 --seed 0 --threads 1 --json \
      --controller "$c" > "$out/vbeat${k}_nav_$c.json" 2> /dev/null
  done
done
for t in 1 2 3 4; do
  build/apps/plan --anatomy anatomies/validation/rca_validation/rca_validation.stl --target "$t" --budget 5000 --json \
    > "$out/rca_validation_hr0_t$t.json"
done
python3 "$out/summarize.py"
