#!/usr/bin/env bash
# Today's controllers on the validation pool (issue 64): 40 coronary trees drawn by gw-anatomy-pool from the held-apart
# seed 900001 (docs/anatomy_pool.md), one evaluate row of 200 episodes (5 per tree), every wrong branch or stall
# followed by recovery (3 pull-backs: the procedure figure). The shipped rotation actor with the baselines and the
# reachability probes. Nothing here is tuned or chosen: it is the baseline a generalist controller must beat on
# anatomies it never trained on. Run from the repository root after scripts/install.sh:
#   bash results/pool_validation/run.sh            # ~75 min on 2 cores
set -euo pipefail
OUT=results/pool_validation
POOL=${POOL:-runs/pool/validation}
.venv/bin/gw-anatomy-pool --out $POOL --count 40 --seed 900001 --jobs 2 > /dev/null
build/apps/evaluate --rows $POOL/index.json --out $OUT/rotation --threads 2 --recovery 3
.venv/bin/python $OUT/summarize.py $OUT/rotation/results.json > $OUT/summary.json
