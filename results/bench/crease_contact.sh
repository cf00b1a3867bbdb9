#!/usr/bin/env bash
# A contact point wedged in a crease held by both walls (engine/contact/detect_contacts.hpp kCreaseDepthMm;
# docs/physics.md "A tip wedged in a crease"), measured at its first depth, 0.02 mm (3fff197; 0.01 mm since
# crease_depth.sh, which measures that step): the bench insertions that never go that deep into a wall are
# bit-identical (their hashes), the jam's halvings and time per sub-step are compared with the build before, and
# the table's outcomes with the build before (runs/equivalence/pivot_inverse, made by pivot_inverse.sh at its
# commit, where present) and the published table. The steps are engine_change.sh's. Run from the repository root
# after `bash scripts/install.sh`:
#   OLD=/path/to/bench-mechanics-of-the-commit-before bash results/bench/crease_contact.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
before=results/results.json
if [ -f runs/equivalence/pivot_inverse/results.json ]; then
  before="runs/equivalence/pivot_inverse/results.json $before"
fi
NAME=crease_contact CASES="jam pl_validation t3 coronary" BEFORE="$before" \
WHAT="bench-mechanics --scaling-substeps 1 with a point wedged in a crease held by both walls (new) and, where \
measured, the build before (old); and the table's outcomes against the build before and the published table \
(results/bench/crease_contact.sh)" \
  bash results/bench/engine_change.sh
