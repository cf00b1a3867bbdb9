#!/usr/bin/env bash
# The generalist's reference points on the validation episodes select.sh scores, with the same pool, step-time limit
# and episodes, so that results/generalist/compare.py pairs them episode by episode. Never a test row.
#   start      the run's start as train.sh builds it: the shipped rotation actor widened to act/2 and obs/8
#              (export_actor.widen_to_push_pull, widen_to_tip_force: its aim, a near-constant push, the new inputs
#              unread), with the run's task training/tasks/generalist.json
#   push_pull  the shipped push/pull actor with its own task (training/tasks/push_pull.json: act/2, obs/5, recovery 3)
#   planned    the start's column again and every episode planned from its own start (evaluate --planned-seeds
#              episodes, 5,000 env steps a search, tip force within 1.5 N): what a procedure reaches from those starts
#   EPISODES=0:100 bash results/generalist/baseline.sh     # then: python results/generalist/compare.py A B
#   NAMES=planned DISTRIBUTION=full EPISODES=0:100 bash results/generalist/baseline.sh   # only some of them
set -euo pipefail
cd "$(dirname "$0")/../.."
source results/generalist/validation_pool.sh  # RUN, POOL, EPISODES -> range and tag; the pool drawn
mkdir -p "$RUN/selection"
start="$RUN/selection/start_actor.json"
[ -f "$start" ] || .venv/bin/python -c '
import json, sys
from guidewire_nav.export_actor import widen_for_task
d = widen_for_task(json.load(open(sys.argv[1])), "guidewire-nav/obs/8", "guidewire-nav/act/2")
json.dump(d, open(sys.argv[2], "w"))' policy/trained/sac_actor.json "$start"
for name in ${NAMES:-start push_pull planned}; do
  out="$RUN/selection/$name$tag"
  plan=()
  if [ "$name" = push_pull ]; then actor=(policy/trained/sac_actor_push_pull.json training/tasks/push_pull.json)
  else actor=("$start" training/tasks/generalist.json); fi
  if [ "$name" = planned ]; then plan=(--planned-seeds episodes --plan-budget 5000); fi
  if [ ! -f "$out/results.json" ]; then
    build/apps/evaluate --rows "$POOL/index.json" --controllers policy --policy "${actor[0]}" --task "${actor[1]}" \
      --reachability-seeds 0 --step-time-limit 1 --threads 2 "${range[@]}" "${plan[@]}" --out "$out" > /dev/null
  fi
  echo "$out/results.json"
done
