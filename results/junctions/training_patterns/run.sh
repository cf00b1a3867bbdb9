#!/usr/bin/env bash
# The shipped obs/3 actor on the two k-way training patterns (docs/junctions.md): 6 episodes a target, seeds 100-105,
# the paper's junction reading (separate) and kway. Writes one navigate JSON per pattern and reading here.
# Run from the repository root after `bash scripts/install.sh`:   bash results/junctions/training_patterns/run.sh
set -euo pipefail
cd "$(dirname "$0")/../../.."
out=results/junctions/training_patterns
for p in t5_trifurcation_planar t6_trifurcation_spread; do
  for j in separate kway; do
    build/apps/navigate --anatomy anatomies/train_junctions/$p/$p.stl --target all --episodes 6 --seed 100 \
      --junctions $j --threads 2 --json > $out/${p}_$j.json
  done
done
