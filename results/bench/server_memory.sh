#!/usr/bin/env bash
# Memory of a training server (issue 62/64): guidewire-server holding every anatomy of the training pool (100
# coronary trees, gw-anatomy-pool seed 1), its resident set once it listens, into results/bench/server_memory.json.
# Run from the repository root after `bash scripts/install.sh`:   bash results/bench/server_memory.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
.venv/bin/gw-anatomy-pool --out runs/pool/train --count 100 --seed 1 --jobs 2 > /dev/null
log=$(mktemp)
build/apps/guidewire-server --anatomies runs/pool/train/index.json --port 0 > "$log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true; rm -f "$log"' EXIT
for _ in $(seq 600); do grep -q listening "$log" && break; sleep 1; done
grep -q listening "$log" || { echo "guidewire-server did not start: $(cat "$log")" >&2; exit 1; }
rss_kb=$(awk '/VmRSS/ {print $2}' /proc/$pid/status)
anatomies=$(.venv/bin/python -c "import json; print(len(json.load(open('runs/pool/train/index.json'))['anatomies']))")
commit=$(git rev-parse --short HEAD)
.venv/bin/python - "$rss_kb" "$anatomies" "$commit" <<'PY'
import json, sys, datetime
rss_kb, anatomies, commit = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
out = {"what": "resident memory of guidewire-server holding the training pool (results/bench/server_memory.sh)",
       "commit": commit, "date": datetime.date.today().isoformat(), "anatomies": anatomies,
       "rss_mb": round(rss_kb / 1024, 1), "mb_per_anatomy": round(rss_kb / 1024 / anatomies, 1)}
open("results/bench/server_memory.json", "w").write(json.dumps(out, indent=2) + "\n")
print(json.dumps(out))
PY
