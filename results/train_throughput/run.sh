#!/usr/bin/env bash
# Training throughput (issue 62 items 4-5): where a training step's time goes, and the shipped schedule against
# the fed one after the same wall time, scored zero-shot on the validation trees. Step-bounded: each run stops at
# its --total-steps (chosen so that both take about the same wall time on a 2-core machine; the wall times
# are measured, not assumed: summary.json). Run from the repository root after scripts/install.sh:
#   bash results/train_throughput/run.sh            # ~50 min on 2 cores
set -euo pipefail
OUT=results/train_throughput
RUNS=${RUNS:-runs/train_throughput}
PY=.venv/bin/python
SHIPPED_STEPS=${SHIPPED_STEPS:-40000}
FED_STEPS=${FED_STEPS:-100000}

# 1. the breakdown: simulation, socket, replay, gradient; whole loop per config
$PY -m guidewire_nav.bench_train --steps 600 --configs shipped,fed --out $OUT/bench.json > /dev/null

# 2. the same seed, the same anatomies and task; only the update schedule differs
common="--envs 2 --seed 0 --eval-episodes 0 --checkpoint-every 10000 --no-progress"
$PY -m guidewire_nav.train $common --total-steps $SHIPPED_STEPS --out $RUNS/shipped
$PY -m guidewire_nav.train $common --total-steps $FED_STEPS --train-freq 4 --gradient-steps 2 --net-arch 256,256 \
  --out $RUNS/fed

# 3. zero-shot scores of the checkpoints on the validation trees (seeds 1000+, 150 episodes each; the training
#    anatomies are not scored here)
score="--train-episode-scale 0 --json"
$PY -m guidewire_nav.score_checkpoints $RUNS/shipped --steps 10000,20000,30000,final --out $OUT/scores_shipped.json $score > /dev/null
$PY -m guidewire_nav.score_checkpoints $RUNS/fed --steps 20000,40000,60000,80000,final --out $OUT/scores_fed.json $score > /dev/null

# 4. success against env steps and against wall minutes
$PY $OUT/summarize.py --runs $RUNS --out $OUT
