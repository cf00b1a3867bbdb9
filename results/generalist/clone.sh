#!/usr/bin/env bash
# The generalist controller cloned from the procedure planner (issue 64, results/generalist/README.md "Cloned from
# the planner"), step-bounded and resumable (every stage is skipped when its output is there):
# 1. the planner's plans from the starts of the first PLANS episodes (default 100) of the training pool (the 100
#    coronary trees of seed 1: every target, one start each, in gw-plan-demos' seeded order), obs/8 and act/2;
# 2. actor_0: an actor fitted to them (gw-clone-plans, started from the shipped rotation actor widened as gw-train
#    widens it);
# 3. ROUNDS rounds (default 1) of relabelling: actor_{r-1} runs the first LEAD_PLANS episodes (default 150) and the
#    planner plans each from 1 s before where it stopped getting deeper (gw-plan-demos --lead-in), and actor_r is
#    fitted to every plan so far (DAgger's loop, with the planner as the expert, once per episode);
# 4. each actor on the validation pool (seed 900001, never a test row) with the generalist's task, as select.sh
#    scores a checkpoint, with control CONTROL (default auto, the generalist task's; always: on every step, as the
#    planner's task has it).
#   bash results/generalist/clone.sh        # EPISODES=0:100 scores only those validation episodes (as select.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT=${OUT:-runs/generalist_clone}
RUN=$OUT
source results/generalist/validation_pool.sh  # POOL, EPISODES -> range and tag; the validation pool drawn
CONTROL=${CONTROL:-auto}
.venv/bin/gw-anatomy-pool --out runs/pool/train --count 100 --seed 1 --jobs 2 > /dev/null
plans() {  # plans OUT_DIR EPISODES [--lead-in ACTOR]: the planner's demonstrations on the training pool
  local dir=$1 count=$2; shift 2
  if [ ! -f "$dir/plans.jsonl" ] || [ "$(wc -l < "$dir/plans.jsonl")" -lt "$count" ]; then
    .venv/bin/gw-plan-demos --anatomies runs/pool/train/index.json --out "$dir" --seed 1 --jobs 2 \
      --max-episodes "$count" "$@" > /dev/null
  fi
}
clone() {  # clone ACTOR DEMOS...: an actor fitted to these demonstrations
  local actor=$1; shift
  [ -f "$actor" ] || .venv/bin/gw-clone-plans --demos "$@" --init-actor policy/trained/sac_actor.json --seed 1 \
    --out "$actor" > "${actor%.json}.log"
}
score() {  # score ACTOR NAME: the actor on the validation pool
  local dir="$OUT/selection/$2_$CONTROL$tag"
  [ -f "$dir/results.json" ] || build/apps/evaluate --rows "$POOL/index.json" --controllers policy --policy "$1" \
    --task training/tasks/generalist.json --control "$CONTROL" --reachability-seeds 0 --step-time-limit 1 \
    --threads "${THREADS:-2}" "${range[@]}" --out "$dir" > /dev/null
  echo "$2 ($CONTROL): $(.venv/bin/python results/pool_validation/summarize.py "$dir/results.json" | tr -d '\n')"
}
plans "$OUT/demos" "${PLANS:-100}"
demos=("$OUT/demos")
clone "$OUT/actor_0.json" "${demos[@]}"
score "$OUT/actor_0.json" actor_0
for ((r = 1; r <= ${ROUNDS:-1}; r++)); do
  plans "$OUT/demos_lead_$((r - 1))" "${LEAD_PLANS:-150}" --lead-in "$OUT/actor_$((r - 1)).json"
  demos+=("$OUT/demos_lead_$((r - 1))")
  clone "$OUT/actor_$r.json" "${demos[@]}"
  score "$OUT/actor_$r.json" "actor_$r"
done
