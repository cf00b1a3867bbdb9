#!/usr/bin/env bash
# Adaptive stepping (issue 62 item 3; WireParams::max_free_substep_s, docs/physics.md "Adaptive stepping"): the
# aortic wire (engine/wire/aortic_035_angled.json, 2 ms sub-steps in free lumen, 0.5 ms at the wall) against the
# same wire with every sub-step 0.5 ms (max_free_substep_s 0), on the three validation arches
# (anatomies/validation/arches, never a test row):
# 1. bench-mechanics, 150 mm inserted from the descending aorta, adaptive and fixed in turn ROUNDS times (default
#    3): simulated time per wall second (control steps of 10 ms per second), its pairwise ratio, long sub-steps,
#    halvings, deepest penetration and the tips' distance.
# 2. The same episodes with both (navigate, the shipped policy, EPISODES per target, default 25, seeds 0..): the
#    outcome and step count of each, and the wall time of each run (the two run side by side, one core each).
# 3. The coronary wire's trajectory hashes (coronary insertion, t3, pl_validation): its sub-steps are unchanged
#    (max_free_substep_s 0), so the hashes are those of the build before.
# Run from the repository root after `bash scripts/install.sh`: bash results/bench/adaptive_stepping.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
ROUNDS=${ROUNDS:-3}
EPISODES=${EPISODES:-25}
out=results/bench/adaptive_stepping.json
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
wire=engine/wire/aortic_035_angled.json
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['max_free_substep_s']=0; json.dump(d,open(sys.argv[2],'w'))" \
  "$wire" "$tmp/fixed.json"
for k in 1 2 3; do
  build/apps/anatomy-gen --spec anatomies/validation/arches/arch_val_type$k.spec.json --out "$tmp/arches" > /dev/null
done
for k in 1 2 3; do
  for round in $(seq 1 "$ROUNDS"); do
    for variant in adaptive fixed; do
      params=$wire
      if [ "$variant" = fixed ]; then params=$tmp/fixed.json; fi
      build/apps/bench-mechanics --anatomy "$tmp/arches/arch_val_type$k" --params "$params" --length 150 \
        --scaling-substeps 1 > "$tmp/bench_${k}_${variant}_$round.json"
    done
  done
done
if [ "$EPISODES" -gt 0 ]; then
  for variant in adaptive fixed; do
    params=$wire
    if [ "$variant" = fixed ]; then params=$tmp/fixed.json; fi
    (for k in 1 2 3; do
       start=$(date +%s.%N)
       build/apps/navigate --anatomy "$tmp/arches/arch_val_type$k.stl" --wire "$params" --target all \
         --episodes "$EPISODES" --seed 0 --threads 1 --json > "$tmp/episodes_${k}_$variant.json" 2> /dev/null || true
       python3 -c "import sys,time; print(time.time() - float(sys.argv[1]))" "$start" > "$tmp/episodes_${k}_$variant.time"
     done) &
  done
  wait
fi
declare -A coronary=([coronary]=anatomies/test/coronary/coronary
                     [t3]=anatomies/train/t3_out_of_plane_steep/t3_out_of_plane_steep
                     [pl_validation]=anatomies/validation/pl_validation/pl_validation)
for case in coronary t3 pl_validation; do
  build/apps/bench-mechanics --anatomy "${coronary[$case]}" --scaling-substeps 1 > "$tmp/coronary_$case.json"
done
python3 - "$tmp" "$out" "$ROUNDS" "$EPISODES" <<'PY'
import datetime, json, math, pathlib, statistics, subprocess, sys
tmp, out, rounds, episodes = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
result = {"what": "the aortic wire with adaptive stepping (2 ms sub-steps in free lumen, 0.5 ms at the wall) against "
                  "every sub-step 0.5 ms, on the validation arches (results/bench/adaptive_stepping.sh)",
          "commit": commit, "date": datetime.date.today().isoformat(), "arches": {}}
for k in (1, 2, 3):
    runs = {v: [json.loads((tmp / f"bench_{k}_{v}_{r}.json").read_text()) for r in range(1, rounds + 1)]
            for v in ("adaptive", "fixed")}
    entry = {}
    for v, rs in runs.items():
        ins = rs[0]["insertion"]
        entry[v] = {"free_span": rs[0]["free_span"], "control_steps": ins["control_steps"],
                    "long_substeps": ins["long_substeps"], "split_substeps": ins["split_substeps"],
                    "max_penetration_mm": ins["max_penetration_mm"], "mean_contacts": ins["mean_contacts"],
                    "ok": ins["ok"], "tip": ins["tip"],
                    "control_steps_per_s_median": round(statistics.median(r["insertion"]["control_steps_per_s"] for r in rs), 1)}
    ratios = [a["insertion"]["control_steps_per_s"] / f["insertion"]["control_steps_per_s"]
              for a, f in zip(runs["adaptive"], runs["fixed"])]
    entry["speed_ratio_adaptive_over_fixed_pairwise_median"] = round(statistics.median(ratios), 3)
    entry["speed_ratio_min_max"] = [round(min(ratios), 3), round(max(ratios), 3)]
    entry["tip_distance_mm"] = round(math.dist(entry["adaptive"]["tip"], entry["fixed"]["tip"]), 4)
    if episodes > 0:
        eps = {v: json.loads((tmp / f"episodes_{k}_{v}.json").read_text()) for v in ("adaptive", "fixed")}
        key = lambda r: (r["target"], r["seed"])
        a = {key(r): r for r in eps["adaptive"]["results"]}
        f = {key(r): r for r in eps["fixed"]["results"]}
        entry["episodes"] = {
            "count": len(a), "same_outcome": sum(a[x]["outcome"] == f[x]["outcome"] for x in a),
            "same_steps": sum(a[x]["steps"] == f[x]["steps"] for x in a),
            "successes": {v: eps[v]["successes"] for v in eps}, "outcomes": {v: eps[v]["outcomes"] for v in eps},
            "differing": [{"target": x[0], "seed": x[1], "fixed": f[x]["outcome"], "adaptive": a[x]["outcome"]}
                          for x in a if a[x]["outcome"] != f[x]["outcome"]],
            "wall_s": {v: round(float((tmp / f"episodes_{k}_{v}.time").read_text()), 1) for v in ("adaptive", "fixed")}}
    result["arches"][f"arch_val_type{k}"] = entry
result["coronary_wire_hashes"] = {c: json.loads((tmp / f"coronary_{c}.json").read_text())["insertion"]["trajectory_hash"]
                                  for c in ("coronary", "t3", "pl_validation")}
out.write_text(json.dumps(result, indent=1) + "\n")
print(json.dumps({k: {"speed_ratio": v["speed_ratio_adaptive_over_fixed_pairwise_median"],
                      "same_outcome": v.get("episodes", {}).get("same_outcome")} for k, v in result["arches"].items()}))
PY
