"""Tables of results/with_recovery/README.md (standard library only).

results.json here: the results table's evaluate run with `--recovery 3` (and `--reachability-seeds 0`), every other
setting the table's. Its strict figures are checked episode by episode against the runs without recovery (REFERENCES:
../results.json for the paper's ten rows, the beating-heart and junction rows' own runs), and the
procedures with recovery are compared, controller against controller, on the same episodes with the exact sign test
the table uses. Then a compact strict -> with recovery table, and per row the episodes that no procedure in any
results.json under results/ reaches. Rows not run yet are left out.
"""
import glob
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from stats import rate, run_episodes, sign_test  # noqa: E402  (results/stats.py)

COLUMNS = [("sac-policy", "SAC (shipped policy)"), ("scripted-omega", "scripted omega"),
           ("scripted-omega-ccw", "scripted omega, other way"), ("push-only", "push-only")]
SAME_STRICT = ("outcome", "steps", "sim_time_s")
# Where the table's rows were measured without recovery: the paper's ten rows, then the rows added since (the first
# file that has a row and column is its reference).
REFERENCES = ["../results.json", "../beating_heart/ceiling/results.json", "../junctions/separate/results.json",
              "../junctions/separate_close/results.json", "../junctions/separate_outer_50/results.json"]


def reference(row, column):
    for path in REFERENCES:
        found = run_episodes(os.path.join(HERE, path), row, column)
        if found:
            return found, path
    return {}, None


def mean(xs):
    return sum(xs) / len(xs) if xs else float("nan")


def strict_table(path, rows):
    """In: this folder's results.json and its rows. Prints the table per row x controller: strict success, the
    episodes whose strict outcome, steps and time match the reference run without recovery, success with recovery,
    mean pull-backs, mean procedure time and peaks over 1.5 N."""
    print("| row | controller | strict | same strict outcome, steps and time as measured without recovery | with recovery (K = 3) | "
          "pull-backs (mean) | procedure time, s (mean) | peak node > 1.5 N (with recovery) |")
    print("|---|---|---|---|---|---|---|---|")
    for row in rows:
        for column, label in COLUMNS:
            run = run_episodes(path, row, column)
            if not run:
                continue
            table, where = reference(row, column)
            n = len(run)
            strict = sum(e["outcome"] == "success" for e in run.values())
            same = sum(k in table and all(table[k][f] == e[f] for f in SAME_STRICT) for k, e in run.items())
            same = f"{same}/{n} ({where[3:]})" if where else "not measured before"
            rec = [e["recovery"] for e in run.values()]
            over = sum(r["force"]["peak_node_N"] > 1.5 for r in rec)
            print(f"| {row} | {label} | {rate(strict, n)} | {same} | "
                  f"{rate(sum(r['outcome'] == 'success' for r in rec), n)} | {mean([r['attempts'] for r in rec]):.2f} | "
                  f"{mean([r['procedure_time_s'] for r in rec]):.1f} | {over}/{n} |")


def comparison_table(path, rows):
    """In: results.json and its rows. Prints, per row, the SAC policy against each scripted omega with recovery on
    the same episodes: won, lost and the exact sign test's p."""
    print("| row | comparison (with recovery, same episodes) | won | lost | p (sign test) |")
    print("|---|---|---|---|---|")
    for row in rows:
        runs = {c: run_episodes(path, row, c) for c, _ in COLUMNS}
        for a, b in [("sac-policy", "scripted-omega"), ("sac-policy", "scripted-omega-ccw")]:
            if not runs[a] or not runs[b]:
                continue
            keys = [k for k in runs[a] if k in runs[b]]
            ok = {c: {k: runs[c][k]["recovery"]["outcome"] == "success" for k in keys} for c in (a, b)}
            won = sum(ok[a][k] and not ok[b][k] for k in keys)
            lost = sum(ok[b][k] and not ok[a][k] for k in keys)
            print(f"| {row} | {dict(COLUMNS)[a]} against {dict(COLUMNS)[b]} | {won} | {lost} | "
                  f"{sign_test(won, lost):.3f} |")


def compact_table(path, rows):
    """In: results.json and its rows. Prints the compact table: per row and controller, strict success -> success
    with recovery (mean pull-backs, mean procedure time)."""
    print("Each cell: strict success -> success with recovery (mean pull-backs, mean procedure time in simulated s).")
    print()
    print("| row | episodes | " + " | ".join(label for _, label in COLUMNS) + " |")
    print("|---|---|" + "---|" * len(COLUMNS))
    for row in rows:
        cells = []
        for column, _ in COLUMNS:
            run = run_episodes(path, row, column)
            rec = [e["recovery"] for e in run.values()]
            strict = sum(e["outcome"] == "success" for e in run.values())
            won = sum(r["outcome"] == "success" for r in rec)
            cells.append(f"{100 * strict / len(run):.0f}% -> {100 * won / len(run):.0f}% "
                         f"({mean([r['attempts'] for r in rec]):.2f}, {mean([r['procedure_time_s'] for r in rec]):.1f})"
                         if run else "-")
        n = max((len(run_episodes(path, row, c)) for c, _ in COLUMNS), default=0)
        print(f"| {row} | {n} | " + " | ".join(cells) + " |")


def reached_table(path, rows):
    """In: results.json and its rows. Prints, per row, how many of this run's episodes some procedure in any
    results.json under results/ reaches, the ones none reaches, and how many files have the row."""
    print("Reached by any procedure run so far: every results.json under results/ with this row (any controller, with "
          "or without recovery, tip reshape, force limit, assist, any actor), over this run's episodes.")
    print()
    print("| row | reached by some run | never reached (anatomy T target seed) | runs with this row |")
    print("|---|---|---|---|")
    everything = sorted(glob.glob(os.path.join(os.path.dirname(HERE), "**", "results.json"), recursive=True))
    for row in rows:
        keys = set().union(*(run_episodes(path, row, c).keys() for c, _ in COLUMNS))
        reached, files = set(), 0
        for other in everything:
            runs = [run_episodes(other, row, c) for c, _ in COLUMNS]
            files += any(runs)
            reached |= {k for run in runs for k, e in run.items() if k in keys and any(
                isinstance(x, dict) and x.get("outcome") == "success" for x in (e, e.get("recovery"), e.get("reshape")))}
        missed = ", ".join(f"{a} T{t} s{sd}" for a, t, sd in sorted(keys - reached)) or "none"
        print(f"| {row} | {rate(len(reached), len(keys))} | {missed} | {files} |")


def main():
    path = os.path.join(HERE, "results.json")
    rows = [r["name"] for r in json.load(open(path))["rows"]] if os.path.exists(path) else []
    strict_table(path, rows)
    print()
    comparison_table(path, rows)
    print()
    compact_table(path, rows)
    print()
    reached_table(path, rows)

if __name__ == "__main__":
    main()
