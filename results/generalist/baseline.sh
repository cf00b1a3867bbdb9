#!/usr/bin/env bash
# The generalist's starting point on the validation episodes select.sh scores: the shipped push/pull actor with its
# own task (training/tasks/push_pull.json: act/2, obs/5, recovery 3), the same pool, step-time limit and episodes, so
# that results/generalist/compare.py pairs them episode by episode. Never a test row.
#   EPISODES=0:100 bash results/generalist/baseline.sh     # then: python results/generalist/compare.py A B
set -euo pipefail
cd "$(dirname "$0")/../.."
source results/generalist/validation_pool.sh  # RUN, POOL, EPISODES -> range and tag; the pool drawn
out="$RUN/selection/push_pull$tag"
if [ ! -f "$out/results.json" ]; then
  build/apps/evaluate --rows "$POOL/index.json" --controllers policy --policy policy/trained/sac_actor_push_pull.json \
    --task training/tasks/push_pull.json --reachability-seeds 0 --step-time-limit 1 --threads 2 "${range[@]}" \
    --out "$out" > /dev/null
fi
echo "$out/results.json"
