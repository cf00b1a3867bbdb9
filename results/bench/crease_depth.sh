#!/usr/bin/env bash
# The crease contact's depth lowered from 0.02 to 0.01 mm (engine/contact/detect_contacts.hpp kCreaseDepthMm;
# docs/physics.md "A tip wedged in a crease"), chosen on the jam among 0.005, 0.01 and 0.02: the bench insertions
# against the 0.02 mm build, and the table's outcomes against that build's equivalence run
# (runs/equivalence/crease_contact, made by crease_contact.sh, where present) and the published table. The steps are
# engine_change.sh's. Run from the repository root after `bash scripts/install.sh`:
#   OLD=/path/to/bench-mechanics-with-0.02 bash results/bench/crease_depth.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
before=results/results.json
if [ -f runs/equivalence/crease_contact/results.json ]; then
  before="runs/equivalence/crease_contact/results.json $before"
fi
NAME=crease_depth CASES="jam pl_validation t3 coronary" BEFORE="$before" \
WHAT="bench-mechanics --scaling-substeps 1 with the crease contact from 0.01 mm into a wall (new) and, where measured, \
from 0.02 mm (old); and the table's outcomes against the 0.02 mm build and the published table \
(results/bench/crease_depth.sh)" \
  bash results/bench/engine_change.sh
