"""Is an engine change statistically equivalent on the table (issue 62: "same outcome on >= 99% of the table's
episodes")? Two evaluate results.json of the same rows, controllers and seeds, one run before the change and one
after, compared episode by episode.

    python results/bench/equivalence.py BEFORE/results.json AFTER/results.json

Output (JSON on stdout): per row and controller, the episodes both ran, how many kept their outcome, how many kept
their outcome and step count (the same episode to the env step), the successes before and after, the episodes only
one of the two reached and the sign test's p on them; then the same over everything, with the share of episodes
whose outcome is unchanged, and the changed episodes listed (row, controller, anatomy, target, seed, outcomes).
"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from stats import run_episodes, sign_test  # noqa: E402


def columns(path):
    """(row name, controller) of every column in an evaluate results.json, in its order."""
    with open(path) as f:
        return [(r["name"], c) for r in json.load(f)["rows"] for c in r["results"]]


def compare(before, after, row, column):
    """The counts of one row's column, and its changed episodes."""
    a, b = run_episodes(before, row, column), run_episodes(after, row, column)
    keys = sorted(set(a) & set(b))
    out = {"episodes": len(keys), "same_outcome": 0, "same_outcome_and_steps": 0, "success_before": 0,
           "success_after": 0, "only_before": 0, "only_after": 0}
    changed = []
    for k in keys:
        oa, ob = a[k]["outcome"], b[k]["outcome"]
        sa, sb = oa == "success", ob == "success"
        out["success_before"] += sa
        out["success_after"] += sb
        out["only_before"] += sa and not sb
        out["only_after"] += sb and not sa
        if oa == ob:
            out["same_outcome"] += 1
            out["same_outcome_and_steps"] += a[k]["steps"] == b[k]["steps"]
        else:
            changed.append({"row": row, "controller": column, "anatomy": k[0], "target": k[1], "seed": k[2],
                            "before": oa, "after": ob})
    out["p"] = sign_test(out["only_before"], out["only_after"])
    return out, changed


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    before, after = sys.argv[1:]
    for path in (before, after):
        if not os.path.isfile(path):
            sys.exit(f"equivalence: {path}: no such file")
    rows, changed = {}, []
    total = {"episodes": 0, "same_outcome": 0, "same_outcome_and_steps": 0, "success_before": 0, "success_after": 0,
             "only_before": 0, "only_after": 0}
    for row, column in columns(after):
        counts, ch = compare(before, after, row, column)
        if counts["episodes"] == 0:
            continue
        rows.setdefault(row, {})[column] = counts
        changed += ch
        for key in total:
            total[key] += counts[key]
    total["p"] = sign_test(total["only_before"], total["only_after"])
    total["share_same_outcome"] = round(total["same_outcome"] / max(1, total["episodes"]), 4)
    json.dump({"before": before, "after": after, "rows": rows, "all": total, "changed": changed}, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
