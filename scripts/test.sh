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
export GW_TESTS_STRICT=1   # a skipped test fails here (tests/python/conftest.py)
# No exception for pytest's exit 5 ("collected no test"): tests/python holds tests, so collecting
# none means they broke (an import error at collection, a moved folder) and must fail the run.
.venv/bin/python -m pytest -q tests/python
