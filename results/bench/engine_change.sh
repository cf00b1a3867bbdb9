#!/usr/bin/env bash
# What an engine change that is not exact does (issue 62): speed and counts of bench-mechanics insertions, and the
# table's outcomes, with this build against the one before. Used by resultant_stiffness.sh and
# pivot_inverse.sh, which say what changed and where it was chosen.
# 1. bench-mechanics --scaling-substeps 1 on each of CASES: halvings, contact solves, deepest penetration, the share
#    of contact solves stopped at the sweep cap, hash (counts, the same on any machine). With OLD=a bench-mechanics
#    built at the commit before, each is also run with it, new and old in turn ROUNDS times (default 3), and the
#    per-sub-step times' pairwise ratio old/new. Cases: jam (validation-pool tree coronary_900001_0032, gw-anatomy-pool
#    seed 900001, never a test row), pl_validation (the validation tree), t3 (training pattern
#    t3_out_of_plane_steep), coronary (the test tree's coronary insertion, bench-mechanics's default).
# 2. The equivalence run: the paper's table (10 rows, four controllers, 2,200 episodes, seeds 0..; evaluate as in
#    docs/results.md but without reachability) with this build, into EQUIV (resumes), compared episode by episode
#    with each results.json of BEFORE (space-separated; default results/results.json, the published table) by
#    equivalence.py. About 35 min on 2 cores.
# Run from the repository root after `bash scripts/install.sh`:
#   NAME=pivot_inverse CASES="jam coronary" WHAT="..." OLD=/path/to/old/bench-mechanics bash results/bench/engine_change.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
NAME=${NAME:?give NAME: the change (results/bench/NAME.json, runs/equivalence/NAME)}
WHAT=${WHAT:?give WHAT: one sentence on what changed}
CASES=${CASES:-jam coronary}
BEFORE=${BEFORE:-results/results.json}
EQUIV=${EQUIV:-runs/equivalence/$NAME}
ROUNDS=${ROUNDS:-3}
POOL=runs/pool/validation
out=results/bench/$NAME.json
.venv/bin/gw-anatomy-pool --out "$POOL" --count 40 --seed 900001 --jobs 2 > /dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A anatomy=([jam]="$POOL/coronary/coronary_900001_0032/coronary_900001_0032"
                    [pl_validation]=anatomies/validation/pl_validation/pl_validation
                    [t3]=anatomies/train/t3_out_of_plane_steep/t3_out_of_plane_steep
                    [coronary]=anatomies/test/coronary/coronary)
rounds=1
if [ -n "${OLD:-}" ]; then rounds=$ROUNDS; fi
for case in $CASES; do
  for round in $(seq 1 "$rounds"); do
    build/apps/bench-mechanics --anatomy "${anatomy[$case]}" --scaling-substeps 1 > "$tmp/${case}_new_$round.json"
    if [ -n "${OLD:-}" ]; then
      "$OLD" --anatomy "${anatomy[$case]}" --scaling-substeps 1 > "$tmp/${case}_old_$round.json"
    fi
  done
done
resume=()
if [ -f "$EQUIV/results.json" ]; then resume=(--resume); fi
build/apps/evaluate --episode-scale 1.0 --policy policy/trained/sac_actor.json \
  --base-policy policy/trained/sac_actor_base.json --threads 2 --reachability-seeds 0 \
  --rows "training anatomies,sensitivity,tree of training patterns,unseen 4-bifurcation tree,coronary-like,deformed coronary" \
  "${resume[@]}" --out "$EQUIV" > /dev/null
i=0
for before in $BEFORE; do
  .venv/bin/python results/bench/equivalence.py "$before" "$EQUIV/results.json" > "$tmp/equivalence_$i.json"
  i=$((i + 1))
done
.venv/bin/python - "$tmp" "$out" "$WHAT" "$CASES" "$BEFORE" <<'PY'
import datetime, json, pathlib, statistics, subprocess, sys
tmp, out, what, cases, before = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3], sys.argv[4].split(), sys.argv[5]
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
keys = ["substeps", "split_substeps", "contact_solves", "max_penetration_mm", "share_contact_solves_at_sweep_cap",
        "trajectory_hash", "ok"]
def run(path):
    return json.loads(path.read_text())["insertion"]
def us(ins):
    return 1e6 / ins["substeps_per_s"]
result = {"what": what, "commit": commit, "date": datetime.date.today().isoformat()}
for case in cases:
    new = sorted(tmp.glob(f"{case}_new_*.json"))
    old = sorted(tmp.glob(f"{case}_old_*.json"))
    entry = {"new": {k: run(new[0])[k] for k in keys}}
    entry["new"]["us_per_substep_median"] = round(statistics.median(us(run(p)) for p in new), 1)
    if old:
        entry["old"] = {k: run(old[0])[k] for k in keys}
        entry["old"]["us_per_substep_median"] = round(statistics.median(us(run(p)) for p in old), 1)
        ratios = [us(run(o)) / us(run(n)) for o, n in zip(old, new)]
        entry["ratio_old_over_new_per_substep_pairwise_median"] = round(statistics.median(ratios), 3)
        entry["ratio_min_max"] = [round(min(ratios), 3), round(max(ratios), 3)]
    result[case] = entry
result["table_equivalence"] = []
for i, path in enumerate(before.split()):
    eq = json.loads((tmp / f"equivalence_{i}.json").read_text())
    result["table_equivalence"].append({"before": path, "all": eq["all"], "rows": eq["rows"], "changed": eq["changed"]})
out.write_text(json.dumps(result, indent=1) + "\n")
print(f"wrote {out}")
PY
