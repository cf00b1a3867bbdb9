#!/usr/bin/env bash
# Installs everything (idempotent), builds, then runs every test: ctest (C++) and pytest (Python).
# Exits non-zero if anything fails. Both runners print their counts.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install.sh

echo "== C++ tests (ctest) =="
ctest --test-dir build --output-on-failure -j "$(nproc)"

echo "== Python tests (pytest) =="
export GW_BUILD_DIR="$PWD/build"
set +e
.venv/bin/python -m pytest -q tests/python
status=$?
set -e
# pytest exits 5 when it collected no test; that is not a failure of ours.
if [ "$status" -ne 0 ] && [ "$status" -ne 5 ]; then exit "$status"; fi
