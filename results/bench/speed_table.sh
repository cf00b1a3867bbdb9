#!/usr/bin/env bash
# Re-measures the speed table of docs/results.md ("Speed") into results/bench/speed_table.json: each benchmark's own
# JSON as it printed it, with the commit and the machine. One command at a time (each on one core); run it on a quiet
# machine after `bash scripts/install.sh`:   bash results/bench/speed_table.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
B=build/apps
out=results/bench/speed_table.json
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
$B/bench-mechanics > "$tmp/mechanics_coronary.json"
$B/bench-mechanics --anatomy anatomies/train/t3_out_of_plane_steep/t3_out_of_plane_steep --push 10 --length 80 \
  > "$tmp/mechanics_training.json"
$B/bench-env --anatomies train > "$tmp/env.json"
$B/bench-policy --policy policy/trained/sac_actor.json > "$tmp/policy.json"
.venv/bin/python - "$tmp" "$out" <<'PY'
import json, pathlib, platform, subprocess, sys, datetime
tmp, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
record = {"what": "the speed table of docs/results.md, re-measured (results/bench/speed_table.sh)",
          "commit": commit, "date": datetime.date.today().isoformat(),
          "machine": {"cpu": platform.processor() or platform.machine(), "cores": __import__("os").cpu_count()},
          "commands": {"mechanics_coronary": "build/apps/bench-mechanics",
                       "mechanics_training": "build/apps/bench-mechanics --anatomy anatomies/train/t3_out_of_plane_steep/"
                                             "t3_out_of_plane_steep --push 10 --length 80",
                       "env": "build/apps/bench-env --anatomies train",
                       "policy": "build/apps/bench-policy --policy policy/trained/sac_actor.json"}}
for name in record["commands"]:
    record[name] = json.loads((tmp / f"{name}.json").read_text())
out.write_text(json.dumps(record, indent=2) + "\n")
print(f"wrote {out}")
PY
