#!/usr/bin/env bash
# The generalist controller's training run (issue 64 item 2), step-bounded and resumable across sessions: SAC on the
# training pool (100 coronary trees drawn by gw-anatomy-pool, seed 1: docs/anatomy_pool.md) with the task
# training/tasks/generalist.json (act/2: push, pull and rotate; obs/8: obs/5 and the tip's wall force; recovery 3, so
# an episode goes on after a wrong child and pulling back is learnt; a cost of time and of wall force over 1.5 N).
# Fourth version (2026-12-06; results/generalist/README.md "Third version" has the two tries before it): started from
# the shipped rotation actor (its inputs widened to obs/8 with zero weights, its insertion output pushing), whose aim
# reaches 88 of the first 100 validation episodes. The actor is held for its first 10,000 steps while the critics
# learn, and its insertion explores meanwhile (--init-log-std -2.3,0.5: the rotation's std 0.1 before tanh, the
# insertion's 1.6, so the critics see slower pushes and pulls, not only the start's constant push; a critic that
# had seen only that push told the actor to pull everywhere). Then both actions are anchored to the start's
# (--anchor-weight 10,1: the rotation firmly, the insertion lightly, so it leaves the push only where the critics'
# preference outweighs it), every transition is kept (--buffer-size 200000: the pushes of the start stay in the
# critics' data), and the discount is 0.995 (a horizon of ~200 env steps, an episode's length, where the paper's
# 0.98 sees ~50: with the speed in the actor's hands, finishing sooner has to be worth something to the critic).
# Two gradient steps per four env steps (docs/training.md "Where a training step's time goes": as good per wall
# minute as one per step, 2.5 times the env steps; the networks stay 3x256). An env step that takes more than 1 s of
# wall time ends its episode (--step-cutoff: a wire jammed in a 0.3 mm vessel simulates up to 55 times slower,
# docs/physics.md, and held up both workers for minutes; the training data then depend a little on the machine's
# speed, no figure does). No evaluation during training: the checkpoints (every 10,000 steps) are chosen later on the
# validation pool (seed 900001), never on a test row.
# Each call runs at most MINUTES of wall time and goes on from the run's last checkpoint:
#   bash results/generalist/train.sh            # again and again until the 400,000 steps are done
# DISTRIBUTION=full trains on issue 64's whole distribution instead (a run of its own, runs/generalist_full): 200
# anatomies of seed 2, three coronary trees to one aortic arch, every anatomy with its own drawn tip and friction,
# every coronary tree beating at its own 0-120 bpm, each arch with the aortic wire (docs/anatomy_pool.md).
# WRONG_BRANCH_STARTS=F starts that share of the training episodes with the tip just inside a wrong child
# (gw-train --wrong-branch-starts, training/guidewire_nav/wrong_branch_start.py), so that leaving one is learnt: the
# fifth version, on trial (results/generalist/README.md "Wrong-branch starts"); give it its own OUT. ANCHOR=W1,W2
# replaces the anchor's weights (rotation, insertion; default 10,1). PULLBACK=N pulls a share of those starts back out
# of the child, up to N env steps, the tip left aimed into it (gw-train --wrong-branch-pullback; default 0). TASK
# replaces the task (a file or an inline JSON object; default training/tasks/generalist.json): e.g. the fifth trial's
# reward paid for depth along the target's course (results/generalist/README.md "Progress along the course").
set -euo pipefail
cd "$(dirname "$0")/../.."
MINUTES=${MINUTES:-65}
if [ "${DISTRIBUTION:-coronary}" = full ]; then
  OUT=${OUT:-runs/generalist_full}
  POOL=runs/pool/train_full
  .venv/bin/gw-anatomy-pool --out "$POOL" --count 200 --seed 2 --kinds coronary,coronary,coronary,arch \
    --vary-wires --beating --jobs 2 > /dev/null
else
  OUT=${OUT:-runs/generalist}
  POOL=runs/pool/train
  .venv/bin/gw-anatomy-pool --out "$POOL" --count 100 --seed 1 --jobs 2 > /dev/null
fi
resume=()
if [ -f "$OUT/settings.json" ]; then resume=(--resume); fi  # a run already started: go on from its last checkpoint
.venv/bin/gw-train --anatomies "$POOL/index.json" --task "${TASK:-training/tasks/generalist.json}" \
  --init-actor policy/trained/sac_actor.json --init-log-std=-2.3,0.5 --actor-freeze-steps 10000 --learning-starts 300 \
  --anchor-weight "${ANCHOR:-10,1}" --buffer-size 200000 --gamma 0.995 --ent-coef auto_0.02 \
  --train-freq 4 --gradient-steps 2 --total-steps 400000 --envs 2 --eval-episodes 0 --checkpoint-every 10000 \
  --step-cutoff 1 --no-progress --torch-threads 1 --wrong-branch-starts "${WRONG_BRANCH_STARTS:-0}" \
  --wrong-branch-pullback "${PULLBACK:-0}" \
  --max-minutes "$MINUTES" --seed 1 --out "$OUT" "${resume[@]}"
