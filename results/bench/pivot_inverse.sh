#!/usr/bin/env bash
# The block-tridiagonal pivots inverted by a fixed-size Cholesky (issue 62 items 1-2; engine/solver/block_tridiagonal.cpp
# invert_spd6; docs/physics.md "The pivots' inverse, and a contact tolerance that static friction refused"): the same
# inverse to rounding, so the trajectories differ in their last bits and the table's outcomes are compared with the
# build before (runs/equivalence/resultant_stiffness, made by resultant_stiffness.sh at its commit, where present) and
# with the published table. The steps are engine_change.sh's. Run from the repository root after
# `bash scripts/install.sh`:
#   OLD=/path/to/bench-mechanics-of-the-commit-before bash results/bench/pivot_inverse.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
before=results/results.json
if [ -f runs/equivalence/resultant_stiffness/results.json ]; then
  before="runs/equivalence/resultant_stiffness/results.json $before"
fi
NAME=pivot_inverse CASES="jam pl_validation t3 coronary" BEFORE="$before" \
WHAT="bench-mechanics --scaling-substeps 1 with the pivots inverted by a fixed-size Cholesky (new) and, where \
measured, the build before (old); and the table's outcomes against the build before and the published table \
(results/bench/pivot_inverse.sh)" \
  bash results/bench/engine_change.sh
