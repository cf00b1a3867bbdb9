"""Two actors on the same episodes: issue 64's procedure figure (reached by the end of the procedure, the tip's peak
force within 1.5 N throughout), paired episode by episode, with the exact sign test the table uses.

    python results/generalist/compare.py A/results.json B/results.json [--column sac-policy[,scripted-omega]]
        [--markdown]

Inputs: two evaluate results.json run with --recovery (a task with recovery_attempts > 0) on the same rows, seeds
and episodes; --column names the column of both files, or A's and B's apart ("sac-policy,scripted-omega": an
actor against the rule, each run in a folder of its own). Output (JSON on stdout, or a markdown table with
--markdown): per row and in all, each actor's successes on the episodes both ran, the episodes only A won and only
B won, and the sign test's p; beside them the strict figure (the paper's: reached without entering a wrong branch)
of each. An episode missing from one file is left out (and counted as such).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from stats import run_episodes, sign_test  # noqa: E402

LIMIT_N = 1.5


def safe_procedure(episode):
    """Reached by the end of the procedure with the tip's peak force within 1.5 N over the whole procedure."""
    rec = episode.get("recovery", {})
    return rec.get("outcome") == "success" and rec.get("force", {}).get("peak_tip_N", 0.0) <= LIMIT_N


def strict(episode):
    """The paper's figure: reached without entering a wrong branch (the strict episode's own outcome)."""
    return episode.get("outcome") == "success"


def compare(a_path, b_path, column, column_b=None):
    column_b = column_b or column
    with open(a_path) as f:
        rows = [r["name"] for r in json.load(f)["rows"]]
    out = {}
    total = {"episodes": 0, "a": 0, "b": 0, "a_only": 0, "b_only": 0, "unmatched": 0, "a_strict": 0, "b_strict": 0}
    for row in rows:
        a, b = run_episodes(a_path, row, column), run_episodes(b_path, row, column_b)
        if not b:
            continue  # a row B has not run (yet)
        both = sorted(set(a) & set(b))
        fig = {"episodes": len(both), "a": sum(safe_procedure(a[k]) for k in both),
               "b": sum(safe_procedure(b[k]) for k in both),
               "a_only": sum(safe_procedure(a[k]) and not safe_procedure(b[k]) for k in both),
               "b_only": sum(safe_procedure(b[k]) and not safe_procedure(a[k]) for k in both),
               "unmatched": len(set(a) ^ set(b)),
               "a_strict": sum(strict(a[k]) for k in both), "b_strict": sum(strict(b[k]) for k in both)}
        fig["p"] = sign_test(fig["a_only"], fig["b_only"])
        out[row] = fig
        for k in total:
            total[k] += fig[k]
    total["p"] = sign_test(total["a_only"], total["b_only"])
    return {"a": a_path, "b": b_path, "column": column, "column_b": column_b,
            "figure": "procedure, tip within 1.5 N", "rows": out, "all": total}


def markdown(result):
    """The comparison as a table: one line per row and one for all rows."""
    a, b = result["column"], result["column_b"]
    lines = [f"| row | episodes | {a}: procedure, tip <= 1.5 N | {b}: procedure, tip <= 1.5 N | only {a} | "
             f"only {b} | p | {a}: strict | {b}: strict |", "|---|---|---|---|---|---|---|---|---|"]
    for name, fig in list(result["rows"].items()) + [("all rows", result["all"])]:
        lines.append(f"| {name} | {fig['episodes']} | {fig['a']} | {fig['b']} | {fig['a_only']} | {fig['b_only']} | "
                     f"{fig['p']:.2g} | {fig['a_strict']} | {fig['b_strict']} |")
    return "\n".join(lines)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--column", default="sac-policy",
                   help="the column of both files (evaluate's name for --policy), or A's and B's: A,B")
    p.add_argument("--markdown", action="store_true", help="a markdown table instead of JSON")
    args = p.parse_args(argv)
    column, _, column_b = args.column.partition(",")
    for path in (args.a, args.b):
        if not os.path.exists(path):
            sys.exit(f"error: {path}: no such results.json")
    result = compare(args.a, args.b, column, column_b or None)
    if args.markdown:
        print(markdown(result))
    else:
        json.dump(result, sys.stdout, indent=1)
        print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
