"""Tables of results/reshape/README.md from the evaluate runs beside this file (standard library only).

results.json: the scripted omega rule and the shipped rotation-only SAC, each with the recovery wrapper
(--recovery 3) and the tip reshape (--reshape-tip 0.3), on the first 25 episodes of the coronary-like and deformed
coronary rows; push_pull/results.json: the shipped push/pull actor (act/2) on the same episodes, the same way.
Each first pass is checked against the runs made without the reshape on the same episodes:
../push_pull/scripted (scripted rule + wrapper), ../recovery and ../recovery/deformed (rotation-only SAC + wrapper)
and ../push_pull/aim_change (push/pull actor).
Sign tests: exact two-sided binomial on the episodes where exactly one of the two succeeded, as the table's.
"""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from stats import rate, sign_test  # noqa: E402  (results/stats.py)

ROWS = ["coronary-like", "deformed coronary"]
# (label, file beside this one, column, the run without reshape on the same episodes: files and column)
CONTROLLERS = [
    ("scripted omega + wrapper", "results.json", "scripted-omega", ["../push_pull/scripted/results.json"], "scripted-omega"),
    ("shipped SAC (act/1) + wrapper", "results.json", "sac-policy",
     ["../recovery/results.json", "../recovery/deformed/results.json"], "sac-policy"),
    ("push/pull SAC (act/2)", "push_pull/results.json", "sac-policy", ["../push_pull/aim_change/results.json"], "sac-policy"),
]


def rows_of(*paths):
    out = {}
    for p in paths:
        full = os.path.join(HERE, p)
        if os.path.exists(full):
            out.update({r["name"]: r for r in json.load(open(full))["rows"]})
    return out


def episodes(row, column):
    res = row["results"].get(column) if row else None
    return {(e["anatomy"], e["target"], e["seed"]): e for e in res["results"]} if res else {}


def first_pass(e):
    r = e.get("recovery", {})
    return (e["outcome"], e["steps"], e["sim_time_s"], r.get("outcome"), r.get("attempts"), r.get("steps"),
            r.get("procedure_time_s"))


def main():
    runs = {}
    print("| row | controller | strict | with recovery (K = 3) | with reshape (tip 0.3/mm) | reshaped | "
          "procedure time, s (mean, with reshape) | peak node force, N (mean, with reshape) | "
          "episodes with peak node > 1.5 N | first pass as the run without reshape |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for row in ROWS:
        for label, path, column, before_paths, before_column in CONTROLLERS:
            eps = episodes(rows_of(path).get(row), column)
            if not eps:
                continue
            runs[(row, label)] = eps
            before = episodes(rows_of(*before_paths).get(row), before_column)
            same = sum(1 for k, e in eps.items() if k in before and first_pass(before[k]) == first_pass(e))
            n = len(eps)
            strict = sum(e["outcome"] == "success" for e in eps.values())
            rec = sum(e["recovery"]["outcome"] == "success" for e in eps.values())
            sh = [e["reshape"] for e in eps.values()]
            ok = sum(s["outcome"] == "success" for s in sh)
            peaks = [s["force"]["peak_node_N"] for s in sh if "force" in s]
            print(f"| {row} | {label} | {rate(strict, n)} | {rate(rec, n)} | {rate(ok, n)} | "
                  f"{sum(s['reshaped'] for s in sh)} | {sum(s['procedure_time_s'] for s in sh) / n:.1f} | "
                  f"{sum(peaks) / max(1, len(peaks)):.2f} | {sum(p > 1.5 for p in peaks)}/{len(peaks)} | "
                  f"{same}/{n} (of {len(before)}) |")

    print("\n| row | comparison (same episodes) | won | lost | p (sign test) |")
    print("|---|---|---|---|---|")
    for row in ROWS:
        for label, *_ in CONTROLLERS:
            eps = runs.get((row, label))
            if not eps:
                continue
            won = sum(e["reshape"]["outcome"] == "success" and e["recovery"]["outcome"] != "success" for e in eps.values())
            lost = sum(e["reshape"]["outcome"] != "success" and e["recovery"]["outcome"] == "success" for e in eps.values())
            print(f"| {row} | {label}: with reshape vs with recovery | {won} | {lost} | {sign_test(won, lost):.3f} |")
        a, b = runs.get((row, "push/pull SAC (act/2)")), runs.get((row, "scripted omega + wrapper"))
        if a and b:
            keys = [k for k in a if k in b]
            won = sum(a[k]["reshape"]["outcome"] == "success" and b[k]["reshape"]["outcome"] != "success" for k in keys)
            lost = sum(a[k]["reshape"]["outcome"] != "success" and b[k]["reshape"]["outcome"] == "success" for k in keys)
            print(f"| {row} | push/pull SAC (act/2) vs scripted omega + wrapper, both with reshape | {won} | {lost} | "
                  f"{sign_test(won, lost):.3f} |")

    print("\nEpisodes not reached with reshape:\n")
    for (row, label), eps in runs.items():
        for (anatomy, target, seed), e in sorted(eps.items()):
            s = e["reshape"]
            if s["outcome"] != "success":
                print(f"- {row}, {label}: {anatomy} T{target} seed {seed}: {s['outcome']} ({s['detail']})"
                      f"{', after the reshape' if s['reshaped'] else ''}")


if __name__ == "__main__":
    main()
