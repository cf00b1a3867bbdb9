"""What the results scripts share (standard library only): the Wilson interval (z 1.96; the C++ table's
lib/runner/success_statistics.hpp uses the exact 1.95996), the exact sign test the table uses, a success-rate cell,
and one column's episodes of an evaluate results.json."""
import functools
import json
import math
import os


def wilson(k, n, z=1.96):
    """95% Wilson score interval for k successes in n trials ((0, 1) for none)."""
    if n == 0:
        return (0.0, 1.0)
    p = k / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return (max(0.0, c - h), min(1.0, c + h))


def sign_test(won, lost):
    """Exact two-sided sign test on the episodes only one of two controllers won."""
    n = won + lost
    if n == 0:
        return 1.0
    k = min(won, lost)
    return min(1.0, 2 * sum(math.comb(n, i) for i in range(k + 1)) / 2 ** n)


def rate(k, n):
    """A success cell: "k/n (p%, lo-hi%)" with the Wilson interval."""
    lo, hi = wilson(k, n)
    return f"{k}/{n} ({100 * k / n:.0f}%, {100 * lo:.0f}-{100 * hi:.0f}%)"


@functools.lru_cache(maxsize=None)
def _rows(path):
    """The "rows" of the results.json at `path`, read once per script (the summaries ask for each file's rows and
    columns one by one); callers read them, never change them."""
    with open(path) as f:
        return json.load(f)["rows"]


def run_episodes(path, row, column):
    """(anatomy, target, seed) -> episode result of `column` in `row` of the evaluate results.json at `path`
    ({} when the file, the row or the column is not there)."""
    if not os.path.exists(path):
        return {}
    for r in _rows(os.path.normpath(path)):
        if r["name"] == row and column in r["results"]:
            return {(e["anatomy"], e["target"], e["seed"]): e for e in r["results"][column]["results"]}
    return {}
