#!/usr/bin/env bash
# Issue 64 item 3: one actor on every row of the results table (the paper's rows, the junction and beating rows),
# with the generalist's task (training/tasks/generalist.json: act/2, obs/8, recovery 3), and the scripted rule on the
# same episodes (it pushes at a constant speed under act/2 and never pulls back), each in a folder of its own so that
# the rule's run serves every actor; compare.py pairs them. No wall-time limit per step (the figures must not depend
# on the machine). The actor is chosen on the validation pool before this runs (select.sh); nothing here chooses
# anything. Resumable: a row already in the folder is kept.
#   ACTOR=runs/generalist/selection/ckpt_400000.json bash results/generalist/rows.sh   # the actor, ~50 min on 2 cores
#   COLUMN=scripted-omega bash results/generalist/rows.sh                               # the rule, ~45 min
#   ROWS="coronary-like,deformed coronary" ...   THREADS=1 ...                         # some rows; one core
set -euo pipefail
cd "$(dirname "$0")/../.."
COLUMN=${COLUMN:-policy}
OUT=${OUT:-results/generalist/rows}/$COLUMN
actor=()
if [ "$COLUMN" = policy ]; then
  ACTOR=${ACTOR:?give ACTOR=the chosen actor JSON (select.sh exports each checkpoint to RUN/selection/ckpt_STEP.json)}
  actor=(--policy "$ACTOR" --base-policy "$ACTOR")
fi
rows=()
if [ -n "${ROWS:-}" ]; then rows=(--rows "$ROWS"); fi
resume=()
if [ -f "$OUT/results.json" ]; then resume=(--resume); fi
build/apps/evaluate "${actor[@]}" --task training/tasks/generalist.json --controllers "$COLUMN" \
  --reachability-seeds 0 --threads "${THREADS:-2}" "${rows[@]}" "${resume[@]}" --out "$OUT"
