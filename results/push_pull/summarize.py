"""Tables of results/push_pull/README.md from the evaluate runs beside this file (standard library only).

results.json: the push/pull actor (act/2) with --recovery 3 on the coronary-like and deformed coronary rows;
50k/results.json: the run continued (--resume) to its 50,000-step checkpoint; time_cost/results.json: the second
run (a cost of time in the reward, started from the shipped rotation actor); time_cost_1/results.json: the same
run with the time cost raised to 1 a step (2026-12-03); since_progress_training/results.json: the second run's
command with observation obs/7 (--since-progress, 2026-12-03) on the training anatomies (its coronary rows' run was
not finished); aim_change_train/, aim_change/, aim_change_every_row/: the second run's command with the aim paid by
its change (--reward-aim change, 2026-12-03) on the training anatomies, the coronary rows and the other rows;
force_train/, force/: that command with a force cost (--reward-force 0.25, 2026-12-03 evening) on the training
anatomies and the coronary rows;
scripted/results.json: the scripted rule with the
recovery wrapper (--recovery 3) on the same episodes, re-run at this commit; ../recovery/: the shipped
rotation-only SAC with the wrapper (same episodes, seeds 0-24); every_row/results.json: the time-cost actor
(the one that ships) and the scripted rule with the wrapper on the table's other eight rows.
Sign tests: exact two-sided binomial on the episodes where exactly one of the two succeeded, as the table's.
"""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from stats import rate, sign_test  # noqa: E402  (results/stats.py)

COMPARED_ROWS = ["coronary-like", "deformed coronary"]
# every_row/results.json: the shipped push/pull actor and the scripted rule with the wrapper on the table's
# other eight rows (the first half of each row's episodes, as on the coronary rows).
EVERY_ROW_PATH = os.path.join(HERE, "every_row", "results.json")
OTHER_ROWS = [r["name"] for r in json.load(open(EVERY_ROW_PATH))["rows"]] if os.path.exists(EVERY_ROW_PATH) else []
ROWS = OTHER_ROWS + COMPARED_ROWS


def load(*parts):
    path = os.path.join(HERE, *parts)
    return {r["name"]: r for r in json.load(open(path))["rows"]} if os.path.exists(path) else {}


def outcomes(column, recovery):
    """(anatomy, target, seed) -> success, strict or with recovery."""
    return {(e["anatomy"], e["target"], e["seed"]): (e["recovery"]["outcome"] if recovery else e["outcome"]) == "success"
            for e in column["results"]}


def mean(values):
    return sum(values) / len(values) if values else float("nan")


runs = {"push/pull SAC (act/2)": (load("results.json"), "sac-policy"),
        "push/pull SAC (act/2), continued to 50k steps": (load("50k", "results.json"), "sac-policy"),
        "push/pull SAC (act/2), time cost, from the rotation actor": (load("time_cost", "results.json") |
                                                                      load("every_row", "results.json"), "sac-policy"),
        "push/pull SAC (act/2), time cost 1 (= the wrong-branch cost)": (load("time_cost_1", "results.json"), "sac-policy"),
        "push/pull SAC (act/2), obs/7 (since_progress), time cost": (load("since_progress_training", "results.json"),
                                                                     "sac-policy"),
        "push/pull SAC (act/2), aim paid by its change, time cost": (load("aim_change_train", "results.json") |
                                                                     load("aim_change", "results.json") |
                                                                     load("aim_change_every_row", "results.json"),
                                                                     "sac-policy"),
        "push/pull SAC (act/2), aim paid by its change, force cost 0.25/N": (load("force_train", "results.json") |
                                                                            load("force", "results.json"), "sac-policy"),
        "scripted omega + wrapper": (load("scripted", "results.json") | load("every_row", "results.json"),
                                     "scripted-omega"),
        "shipped SAC (act/1) + wrapper": (load("..", "recovery", "results.json") | load("..", "recovery", "deformed",
                                                                                        "results.json"), "sac-policy")}
print("| row | controller | strict | with recovery (K = 3) | retries used (mean) | procedure time, s (mean) | "
      "peak node force, N (mean) | episodes with peak node > 1.5 N |")
print("|---|---|---|---|---|---|---|---|")
for row in ROWS:
    for label, (table, col) in runs.items():
        if row not in table or col not in table[row]["results"]:
            continue
        c = table[row]["results"][col]
        eps = c["results"]
        strict = sum(e["outcome"] == "success" for e in eps)
        rec = sum(e["recovery"]["outcome"] == "success" for e in eps)
        n = len(eps)
        attempts = mean([e["recovery"]["attempts"] for e in eps])
        proc = mean([e["recovery"]["procedure_time_s"] for e in eps])
        peak = [e["recovery"]["force"]["peak_node_N"] for e in eps]
        print(f"| {row} | {label} | {rate(strict, n)} | {rate(rec, n)} | {attempts:.2f} | {proc:.1f} | "
              f"{mean(peak):.2f} | {sum(p > 1.5 for p in peak)}/{n} |")

print()
print("| row | comparison (same episodes) | won | lost | p (sign test) |")
print("|---|---|---|---|---|")
pairs = [("push/pull SAC (act/2)", True, "scripted omega + wrapper", True),
         ("push/pull SAC (act/2), continued to 50k steps", True, "scripted omega + wrapper", True),
         ("push/pull SAC (act/2), time cost, from the rotation actor", True, "scripted omega + wrapper", True),
         ("push/pull SAC (act/2), time cost 1 (= the wrong-branch cost)", True, "scripted omega + wrapper", True),
         ("push/pull SAC (act/2), time cost 1 (= the wrong-branch cost)", True,
          "push/pull SAC (act/2), time cost, from the rotation actor", True),
         ("push/pull SAC (act/2), obs/7 (since_progress), time cost", True, "scripted omega + wrapper", True),
         ("push/pull SAC (act/2), obs/7 (since_progress), time cost", True,
          "push/pull SAC (act/2), time cost, from the rotation actor", True),
         ("push/pull SAC (act/2), aim paid by its change, time cost", True, "scripted omega + wrapper", True),
         ("push/pull SAC (act/2), aim paid by its change, time cost", True,
          "push/pull SAC (act/2), time cost, from the rotation actor", True),
         ("push/pull SAC (act/2), aim paid by its change, time cost", True, "shipped SAC (act/1) + wrapper", True),
         ("push/pull SAC (act/2), aim paid by its change, force cost 0.25/N", True, "scripted omega + wrapper", True),
         ("push/pull SAC (act/2), aim paid by its change, force cost 0.25/N", True,
          "push/pull SAC (act/2), aim paid by its change, time cost", True),
         ("push/pull SAC (act/2), time cost, from the rotation actor", True, "shipped SAC (act/1) + wrapper", True),
         ("push/pull SAC (act/2), time cost, from the rotation actor", False, "shipped SAC (act/1) + wrapper", False),
         ("push/pull SAC (act/2)", True, "shipped SAC (act/1) + wrapper", True),
         ("push/pull SAC (act/2)", False, "shipped SAC (act/1) + wrapper", False)]
for row in ROWS:
    for a, ra, b, rb in pairs:
        ta, ca = runs[a]
        tb, cb = runs[b]
        if row not in ta or row not in tb or ca not in ta[row]["results"] or cb not in tb[row]["results"]:
            continue
        x, y = outcomes(ta[row]["results"][ca], ra), outcomes(tb[row]["results"][cb], rb)
        keys = sorted(set(x) & set(y))
        won = sum(x[k] and not y[k] for k in keys)
        lost = sum(y[k] and not x[k] for k in keys)
        what = f"{a} {'with recovery' if ra else 'strict'} vs {b} {'with recovery' if rb else 'strict'} ({len(keys)})"
        print(f"| {row} | {what} | {won} | {lost} | {sign_test(won, lost):.3f} |")
