#!/usr/bin/env bash
# The contact stage's two inexact speed-ups of 2026-12-06 (issue 62 items 1-2; docs/physics.md "The contact solve's
# velocity tolerance"): projected Gauss-Seidel also stops when a sweep changed no contact's velocity by more than
# 1 mm/s (wire parameter contact_velocity_tolerance_mm_per_s; 0 gives the solver before), and the pivots of the
# block-tridiagonal factorisation are inverted by a fixed-size Cholesky (engine/solver/block_tridiagonal.cpp) instead
# of Eigen's LLT solve on an identity (the same inverse to rounding). The tolerance was chosen on pl_validation, t3 and
# the jam (validation and training anatomies); the coronary insertion (the test tree) was timed only after.
# The table's outcomes are compared with the build before (runs/equivalence/resultant_stiffness, made by
# resultant_stiffness.sh at its commit) and with the published table. The steps are engine_change.sh's.
# Run from the repository root after `bash scripts/install.sh`:
#   OLD=/path/to/bench-mechanics-of-the-commit-before bash results/bench/contact_tolerance.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
before=results/results.json
if [ -f runs/equivalence/resultant_stiffness/results.json ]; then
  before="runs/equivalence/resultant_stiffness/results.json $before"
fi
NAME=contact_tolerance CASES="jam pl_validation t3 coronary" BEFORE="$before" \
WHAT="bench-mechanics --scaling-substeps 1 with the contact solve's velocity tolerance and the fixed-size pivot \
inverse (new) and, where measured, the build before them (old); and the table's outcomes against the build before \
and the published table (results/bench/contact_tolerance.sh)" \
  bash results/bench/engine_change.sh
