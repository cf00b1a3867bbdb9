#!/usr/bin/env bash
# The force resultant's string stiffness in the implicit step (issue 62 item 1; engine/sim/assemble_system.cpp
# add_resultant_stiffness; docs/physics.md "A jammed wire"): what it does to a jam, to the coronary insertion, and to
# the table's outcomes.
# 1. bench-mechanics --scaling-substeps 1 on the jam (validation-pool tree coronary_900001_0032, gw-anatomy-pool seed
#    900001, never a test row) and on the coronary insertion: halvings, contact solves, deepest penetration, hash
#    (counts, the same on any machine). With OLD=a bench-mechanics built at the commit before, each is also run with
#    it, new and old in turn ROUNDS times (default 3), and the per-sub-step times' pairwise ratio old/new.
# 2. The equivalence run: the paper's table (10 rows, four controllers, 2,200 episodes, seeds 0..; evaluate as in
#    docs/results.md but without reachability) with this build, into runs/equivalence/resultant_stiffness (resumes),
#    compared episode by episode with results/results.json by equivalence.py. About 35 min on 2 cores.
# The steps are engine_change.sh's. Run from the repository root after `bash scripts/install.sh`:
#   OLD=/path/to/old/bench-mechanics bash results/bench/resultant_stiffness.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
NAME=resultant_stiffness CASES="jam coronary" BEFORE=results/results.json \
WHAT="bench-mechanics --scaling-substeps 1 with the force resultant's string stiffness (new) and, where measured, \
the build before it (old), on a jam and on the coronary insertion; and the table's outcomes before and after \
(results/bench/resultant_stiffness.sh)" \
  bash results/bench/engine_change.sh
