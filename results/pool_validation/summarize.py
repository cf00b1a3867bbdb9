"""Issue 64's two figures per column of evaluate's results.json files, from their per-episode entries.

    python results/pool_validation/summarize.py A/results.json [B/results.json ...] > summary.json

strict: reached without entering a wrong branch (the paper's episode); procedure: reached by the end of the
procedure (recovery's pull-backs included); each also "at a safe force": with the peak tip force of the strict
episode (the whole procedure) within 1.5 N. Beside them the tip's mean peak force and the share over 1.5 N, and the
body's (any node's) share over 1.5 N.
"""
import json
import sys

LIMIT_N = 1.5


def column_figures(summary):
    eps = summary["results"]
    n = len(eps)

    def tip(force):
        return force.get("peak_tip_N", 0.0)

    strict = [e for e in eps if e["outcome"] == "success"]
    procedure = [e for e in eps if e.get("recovery", {}).get("outcome") == "success"]
    whole = [e.get("recovery", e).get("force", e.get("force", {})) for e in eps]
    return {
        "episodes": n,
        "strict": len(strict),
        "strict_tip_within_1_5N": sum(tip(e.get("force", {})) <= LIMIT_N for e in strict),
        "procedure": len(procedure),
        "procedure_tip_within_1_5N": sum(tip(e["recovery"].get("force", {})) <= LIMIT_N for e in procedure),
        "procedure_mean_peak_tip_N": round(sum(tip(f) for f in whole) / max(n, 1), 3),
        "procedure_share_tip_over_1_5N": round(sum(tip(f) > LIMIT_N for f in whole) / max(n, 1), 3),
        "procedure_share_node_over_1_5N": round(sum(f.get("peak_node_N", 0.0) > LIMIT_N for f in whole) / max(n, 1), 3),
    }


def main(paths):
    out = {}
    for path in paths:
        run = json.load(open(path))
        policy = run["settings"].get("policy", "")
        for row in run["rows"]:
            for column, summary in row.get("results", {}).items():
                name = f"{column} ({policy})" if column == "policy" else column
                out.setdefault(row["name"], {})[name] = column_figures(summary)
            if "ceiling" in row:
                out[row["name"]]["reached by a controller or rotation schedule"] = row["ceiling"]["reached"]
    json.dump(out, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main(sys.argv[1:])
