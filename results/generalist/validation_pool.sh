# Sourced by select.sh and baseline.sh: the run and its validation pool (drawn, or kept when already there), never a
# test row. DISTRIBUTION=full (train.sh's whole-distribution run): drawn as its training pool is, from seed 900002.
if [ "${DISTRIBUTION:-coronary}" = full ]; then
  RUN=${RUN:-runs/generalist_full}
  POOL=${POOL:-runs/pool/validation_full}
  draw=(--count 40 --seed 900002 --kinds coronary,coronary,coronary,arch --vary-wires --beating)
else
  RUN=${RUN:-runs/generalist}
  POOL=${POOL:-runs/pool/validation}
  draw=(--count 40 --seed 900001)
fi
EPISODES=${EPISODES:-}
range=(); tag=""
if [ -n "$EPISODES" ]; then range=(--episodes "$EPISODES"); tag="_e${EPISODES/:/-}"; fi
.venv/bin/gw-anatomy-pool --out "$POOL" "${draw[@]}" --jobs 2 > /dev/null
