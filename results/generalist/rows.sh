#!/usr/bin/env bash
# Issue 64 item 3: one actor on every row of the results table (the paper's rows, the junction and beating rows),
# with the generalist's task (training/tasks/generalist.json: act/2, obs/8, recovery 3), beside the scripted rule on
# the same episodes (it pushes at a constant speed under act/2 and never pulls back), so that compare.py pairs them.
# No wall-time limit per step (the figures must not depend on the machine). The actor is chosen on the validation
# pool before this runs (select.sh); nothing here chooses anything. Resumable: a row already in OUT is kept.
#   ACTOR=runs/generalist/selection/ckpt_400000.json bash results/generalist/rows.sh   # ~95 min on 2 cores
#   ROWS="coronary-like,deformed coronary" ...                                           # some rows only
set -euo pipefail
cd "$(dirname "$0")/../.."
ACTOR=${ACTOR:?give ACTOR=the chosen actor JSON (select.sh exports each checkpoint to RUN/selection/ckpt_STEP.json)}
OUT=${OUT:-results/generalist/rows}
rows=()
if [ -n "${ROWS:-}" ]; then rows=(--rows "$ROWS"); fi
resume=()
if [ -f "$OUT/results.json" ]; then resume=(--resume); fi
build/apps/evaluate --policy "$ACTOR" --base-policy "$ACTOR" --task training/tasks/generalist.json \
  --controllers policy,scripted-omega --reachability-seeds 0 --threads 2 "${rows[@]}" "${resume[@]}" --out "$OUT"
