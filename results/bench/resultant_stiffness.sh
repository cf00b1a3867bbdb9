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
# Run from the repository root after `bash scripts/install.sh`:
#   OLD=/path/to/old/bench-mechanics bash results/bench/resultant_stiffness.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
POOL=runs/pool/validation
EQUIV=${EQUIV:-runs/equivalence/resultant_stiffness}
ROUNDS=${ROUNDS:-3}
out=results/bench/resultant_stiffness.json
.venv/bin/gw-anatomy-pool --out "$POOL" --count 40 --seed 900001 --jobs 2 > /dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A anatomy=([jam]="$POOL/coronary/coronary_900001_0032/coronary_900001_0032"
                    [coronary]=anatomies/test/coronary/coronary)
rounds=1
if [ -n "${OLD:-}" ]; then rounds=$ROUNDS; fi
for case in jam coronary; do
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
.venv/bin/python results/bench/equivalence.py results/results.json "$EQUIV/results.json" > "$tmp/equivalence.json"
.venv/bin/python - "$tmp" "$out" <<'PY'
import datetime, json, pathlib, statistics, subprocess, sys
tmp, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
keys = ["substeps", "split_substeps", "contact_solves", "max_penetration_mm", "share_contact_solves_at_sweep_cap",
        "trajectory_hash", "ok"]
def run(path):
    return json.loads(path.read_text())["insertion"]
def us(ins):
    return 1e6 / ins["substeps_per_s"]
result = {"what": "bench-mechanics --scaling-substeps 1 with the force resultant's string stiffness (new) and, where "
                  "measured, the build before it (old), on a jam and on the coronary insertion; and the table's "
                  "outcomes before and after (results/bench/resultant_stiffness.sh)",
          "commit": commit, "date": datetime.date.today().isoformat()}
for case in ("jam", "coronary"):
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
eq = json.loads((tmp / "equivalence.json").read_text())
result["table_equivalence"] = {"all": eq["all"], "rows": eq["rows"], "changed": eq["changed"]}
out.write_text(json.dumps(result, indent=1) + "\n")
print(f"wrote {out}")
PY
