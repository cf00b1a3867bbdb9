#!/usr/bin/env bash
# Training throughput (issue 62 items 4-5): where a training step's time goes, and the update schedules against
# each other after the same wall time, scored zero-shot on the validation trees. Step-bounded: each run stops at
# its --total-steps (chosen so that the runs take about the same wall time on a 2-core machine; the wall times
# are measured, not assumed: summary.json). Run from the repository root after scripts/install.sh:
#   bash results/train_throughput/run.sh            # ~80 min on 2 cores
# Each run's steps and scored checkpoints can be set (NAME_STEPS=0 skips a run), and OUT and RUNS moved, e.g. the
# 2026-12-07 comparison of fed and overlapped (results/train_throughput/overlap/README.md says the command).
set -euo pipefail
OUT=${OUT:-results/train_throughput}
RUNS=${RUNS:-runs/train_throughput}
PY=.venv/bin/python
SHIPPED_STEPS=${SHIPPED_STEPS:-40000}
FED_STEPS=${FED_STEPS:-100000}
OVERLAPPED_STEPS=${OVERLAPPED_STEPS:-150000}
SHIPPED_SCORED=${SHIPPED_SCORED:-10000,20000,30000,final}
FED_SCORED=${FED_SCORED:-20000,40000,60000,80000,final}
OVERLAPPED_SCORED=${OVERLAPPED_SCORED:-30000,60000,90000,120000,final}
CONFIGS=${CONFIGS:-shipped,fed,overlapped}
BENCH_STEPS=${BENCH_STEPS:-600}
mkdir -p "$OUT"

# 1. the breakdown: simulation, socket, replay, gradient; whole loop per config
$PY -m guidewire_nav.bench_train --steps "$BENCH_STEPS" --configs "$CONFIGS" --out "$OUT/bench.json" > /dev/null

# 2. the same seed, the same anatomies and task; only the update schedule differs:
#    shipped     the paper's: one gradient step per env step, 3x256, 2 servers
#    fed         one gradient step per 4 env steps, 2x256, 2 servers
#    overlapped  fed's ratio with 4 servers, the gradient steps taken while the servers simulate (--overlap)
common="--seed 0 --eval-episodes 0 --checkpoint-every 10000 --no-progress"
declare -A flags=(
  [shipped]="--envs 2"
  [fed]="--envs 2 --train-freq 4 --gradient-steps 2 --net-arch 256,256"
  [overlapped]="--envs 4 --train-freq 2 --gradient-steps 2 --net-arch 256,256 --overlap"
)
declare -A steps=([shipped]=$SHIPPED_STEPS [fed]=$FED_STEPS [overlapped]=$OVERLAPPED_STEPS)
declare -A scored=([shipped]=$SHIPPED_SCORED [fed]=$FED_SCORED [overlapped]=$OVERLAPPED_SCORED)
for run in shipped fed overlapped; do
  [ "${steps[$run]}" -gt 0 ] || continue
  # shellcheck disable=SC2086  # the flags are words
  $PY -m guidewire_nav.train $common ${flags[$run]} --total-steps "${steps[$run]}" --out "$RUNS/$run"
done

# 3. zero-shot scores of the checkpoints on the validation trees (seeds 1000+, 150 episodes each; the training
#    anatomies are not scored here)
for run in shipped fed overlapped; do
  [ "${steps[$run]}" -gt 0 ] || continue
  $PY -m guidewire_nav.score_checkpoints "$RUNS/$run" --steps "${scored[$run]}" --out "$OUT/scores_$run.json" \
    --train-episode-scale 0 --json > /dev/null
done

# 4. success against env steps and against wall minutes (the runs scored above)
$PY results/train_throughput/summarize.py --runs "$RUNS" --out "$OUT"
