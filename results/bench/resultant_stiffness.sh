#!/usr/bin/env bash
# The force resultant's string stiffness in the implicit step (issue 62 item 1; engine/sim/assemble_system.cpp
# add_resultant_stiffness; docs/physics.md "A jammed wire"): what it does to a jam, to the coronary insertion, and to
# the table's outcomes: engine_change.sh's steps on the jam and the coronary insertion, the table run into
# runs/equivalence/resultant_stiffness and compared with results/results.json. Run from the repository root after
# `bash scripts/install.sh`:
#   OLD=/path/to/old/bench-mechanics bash results/bench/resultant_stiffness.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
NAME=resultant_stiffness CASES="jam coronary" BEFORE=results/results.json \
WHAT="bench-mechanics --scaling-substeps 1 with the force resultant's string stiffness (new) and, where measured, \
the build before it (old), on a jam and on the coronary insertion; and the table's outcomes before and after \
(results/bench/resultant_stiffness.sh)" \
  bash results/bench/engine_change.sh
