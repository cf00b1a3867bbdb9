#!/usr/bin/env bash
# Choose the generalist's checkpoint on the validation pool (issue 64): every checkpoint of the training run,
# exported to an actor JSON and run by `evaluate` on the 40 validation trees (gw-anatomy-pool seed 900001, never a
# test row, never trained on), 200 episodes, with the run's task (recovery 3: the procedure goes on after a wrong
# child). As in training, an env step over 1 s of wall time ends its episode as a timeout: a choice between
# checkpoints, made on this machine, not a figure. Checkpoints already scored are kept. Then the strict and procedure
# figures (with the tip within 1.5 N) of each, by results/pool_validation/summarize.py, into RUN/selection/summary.json.
#   bash results/generalist/select.sh            # after results/generalist/train.sh
# On 2 cores each checkpoint takes several minutes: STEPS="300000 400000" scores only those checkpoints, and
# EPISODES=0:100 only the first 100 episodes (kept apart: RUN/selection/STEP_e0-100); THREADS=1 runs it on one
# core (beside another job on the other: each episode then has a core to itself, as with 2 threads on a quiet machine).
set -euo pipefail
cd "$(dirname "$0")/../.."
source results/generalist/validation_pool.sh  # RUN, POOL, EPISODES -> range and tag; the pool drawn
STEPS=${STEPS:-}
mkdir -p "$RUN/selection"
results=()
for zip in "$RUN"/checkpoints/sac_*_steps.zip; do
  [ -e "$zip" ] || { echo "no checkpoint in $RUN/checkpoints" >&2; exit 1; }
  step=$(basename "$zip" _steps.zip); step=${step#sac_}
  if [ -n "$STEPS" ] && [[ " $STEPS " != *" $step "* ]]; then continue; fi
  actor="$RUN/selection/ckpt_$step.json"
  [ -f "$actor" ] || .venv/bin/gw-export "$zip" "$actor" --obs-layout guidewire-nav/obs/8 > /dev/null
  if [ ! -f "$RUN/selection/$step$tag/results.json" ]; then
    build/apps/evaluate --rows "$POOL/index.json" --controllers policy --policy "$actor" \
      --task training/tasks/generalist.json --reachability-seeds 0 --step-time-limit 1 --threads "${THREADS:-2}" \
      "${range[@]}" --out "$RUN/selection/$step$tag" > /dev/null
  fi
  results+=("$RUN/selection/$step$tag/results.json")
done
for r in "${results[@]}"; do  # one summary per checkpoint, keyed by its steps
  echo "$(basename "$(dirname "$r")") $(.venv/bin/python results/pool_validation/summarize.py "$r" | tr -d '\n')"
done | .venv/bin/python -c '
import json, sys
out = {}
for line in sys.stdin:
    step, summary = line.split(" ", 1)
    (row,) = json.loads(summary).values()
    out[step] = row["sac-policy"]
json.dump(dict(sorted(out.items(), key=lambda kv: (int(kv[0].split("_")[0]), kv[0]))), sys.stdout, indent=1)
' > "$RUN/selection/summary$tag.json"
echo "wrote $RUN/selection/summary$tag.json"
