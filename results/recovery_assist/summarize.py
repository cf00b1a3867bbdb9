"""Tables of results/recovery_assist/README.md from the evaluate runs (standard library only).

coronary_like/results.json (the coronary-like row's 200 episodes, seeds 0-199) and deformed/results.json (the deformed
coronary row's 50, seeds 0-49): the shipped push/pull actor (act/2) with --recovery 3 --recovery-assist --reshape-tip 0.3
--force-limit 1.5. Compared episode by episode with the same actor without the assist and with the scripted omega rule
with the recovery wrapper, both with recovery, reshape and the limit, from ../force_limit (results.json and
push_pull/results.json: the rows' first 25 episodes; *_25: episodes 25-49; *_50: the coronary-like row's episodes
50-199). A row's episode k is the same at any episode scale.
every_row/results.json: the same actor with --recovery 3 --recovery-assist only (no reshape, no limit) on the table's
other rows (half their episodes), against ../push_pull/aim_change_every_row and ../push_pull/aim_change_train (the actor
alone, --recovery 3) and ../push_pull/every_row (the scripted rule with the wrapper, --recovery 3).
Sign tests: exact two-sided binomial on the episodes where exactly one of the two succeeded, as the table's.
"""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from stats import rate, run_episodes, sign_test  # noqa: E402  (results/stats.py)

ROWS = [("coronary-like", "coronary_like/results.json"), ("deformed coronary", "deformed/results.json")]
BEFORE = "../force_limit"
STAGES = [("strict", lambda e: e["outcome"]), ("with recovery", lambda e: e["recovery"]["outcome"]),
          ("with reshape", lambda e: e["reshape"]["outcome"])]


def episodes(path, row, column):
    return run_episodes(os.path.join(HERE, path), row, column)


def joined(files, row, column):
    out = {}
    for f in files:
        out.update(episodes(os.path.join(BEFORE, f), row, column))
    return out


def main():
    controllers = {}
    for row, path in ROWS:
        assisted = episodes(path, row, "sac-policy")
        if not assisted:
            continue
        alone = joined(["push_pull/results.json", "push_pull_25/results.json", "push_pull_50/results.json"], row,
                       "sac-policy")
        scripted = joined(["results.json", "scripted_25/results.json", "scripted_50/results.json"], row,
                          "scripted-omega")
        keys = sorted(k for k in assisted if k in alone and k in scripted)
        controllers[row] = (keys, [("push/pull SAC (act/2) + assist", assisted), ("push/pull SAC (act/2) alone", alone),
                                   ("scripted omega + wrapper", scripted)])

    print("| row | controller | strict | with recovery (K = 3) | with reshape (tip 0.3/mm) | pull-backs (mean) | "
          "peak node force, N (mean) | (largest) | peak node > 1.5 N | procedure time, s (mean) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for row, (keys, runs) in controllers.items():
        n = len(keys)
        for label, eps in runs:
            cells = " | ".join(rate(sum(f(eps[k]) == "success" for k in keys), n) for _, f in STAGES)
            peaks = [eps[k]["reshape"].get("force", {}).get("peak_node_N", 0.0) for k in keys]
            attempts = sum(eps[k]["recovery"]["attempts"] for k in keys) / n
            time_s = sum(eps[k]["reshape"]["procedure_time_s"] for k in keys) / n
            print(f"| {row} ({n}) | {label} | {cells} | {attempts:.2f} | {sum(peaks) / n:.2f} | {max(peaks):.2f} | "
                  f"{sum(p > 1.5 for p in peaks)}/{n} | {time_s:.1f} |")

    print("\n| row | stage | comparison | won | lost | p (sign test) |")
    print("|---|---|---|---|---|---|")
    for row, (keys, runs) in controllers.items():
        assisted = runs[0][1]
        for other_label, other in runs[1:]:
            for stage, f in STAGES[1:]:
                won = sum(f(assisted[k]) == "success" and f(other[k]) != "success" for k in keys)
                lost = sum(f(assisted[k]) != "success" and f(other[k]) == "success" for k in keys)
                print(f"| {row} | {stage} | assisted against {other_label} | {won} | {lost} | "
                      f"{sign_test(won, lost):.3f} |")

    print("\nProcedures of the assisted actor that did not reach the target (with reshape), and those the assist changed:\n")
    for row, (keys, runs) in controllers.items():
        assisted, alone, scripted = (r[1] for r in runs)
        for k in keys:
            a, b = assisted[k], alone[k]
            if a["reshape"]["outcome"] != "success" or a["reshape"]["outcome"] != b["reshape"]["outcome"]:
                cut = "env step exceeded" in (a["recovery"]["detail"] + a["reshape"]["detail"])
                print(f"- {row}: {k[0]} T{k[1]} seed {k[2]}: alone {b['recovery']['outcome']}/{b['reshape']['outcome']} -> "
                      f"assisted {a['recovery']['outcome']} after {a['recovery']['attempts']} pull-backs/"
                      f"{a['reshape']['outcome']} (scripted: {scripted[k]['reshape']['outcome']})"
                      f"{'; a pass cut by the wall-time step limit' if cut else ''}")

    every_row()
    standstill()


def standstill():
    """The assist with its standstill trigger (these runs) against the assist before it (before_standstill/)."""
    runs = [("coronary-like", "coronary_like/results.json"), ("deformed coronary", "deformed/results.json")]
    if not os.path.isdir(os.path.join(HERE, "before_standstill")):
        return
    print("\nThe standstill trigger: the assist now against the assist before it, the same episodes:\n")
    print("| row | stage | now | before | won | lost | p (sign test) |")
    print("|---|---|---|---|---|---|---|")
    every = [(r["name"], "every_row/results.json") for r in json.load(open(os.path.join(HERE, "every_row/results.json")))["rows"]]
    for row, path in runs + every:
        now = episodes(path, row, "sac-policy")
        before = episodes(os.path.join("before_standstill", path), row, "sac-policy")
        keys = sorted(k for k in now if k in before)
        stages = STAGES[:2] if path.startswith("every_row") else STAGES
        for stage, f in stages:
            a = sum(f(now[k]) == "success" for k in keys)
            b = sum(f(before[k]) == "success" for k in keys)
            won = sum(f(now[k]) == "success" and f(before[k]) != "success" for k in keys)
            lost = sum(f(now[k]) != "success" and f(before[k]) == "success" for k in keys)
            print(f"| {row} | {stage} | {rate(a, len(keys))} | {rate(b, len(keys))} | {won} | {lost} | "
                  f"{sign_test(won, lost):.3f} |")


def every_row():
    path = os.path.join(HERE, "every_row/results.json")
    if not os.path.exists(path):
        return
    print("\nThe table's other rows, with recovery (K = 3), no reshape, no force limit:\n")
    print("| row | push/pull + assist | push/pull alone | scripted omega + wrapper | assisted against alone: won, lost | "
          "against the scripted rule: won, lost, p |")
    print("|---|---|---|---|---|---|")
    totals = [0, 0, 0, 0, 0, 0, 0]
    for r in json.load(open(path))["rows"]:
        row = r["name"]
        assisted = episodes("every_row/results.json", row, "sac-policy")
        alone = {**episodes("../push_pull/aim_change_every_row/results.json", row, "sac-policy"),
                 **episodes("../push_pull/aim_change_train/results.json", row, "sac-policy")}
        scripted = episodes("../push_pull/every_row/results.json", row, "scripted-omega")
        keys = sorted(k for k in assisted if k in alone and k in scripted)
        n = len(keys)
        ok = [sum(d[k]["recovery"]["outcome"] == "success" for k in keys) for d in (assisted, alone, scripted)]
        f = lambda e: e["recovery"]["outcome"] == "success"  # noqa: E731
        won_a = sum(f(assisted[k]) and not f(alone[k]) for k in keys)
        lost_a = sum(not f(assisted[k]) and f(alone[k]) for k in keys)
        won_s = sum(f(assisted[k]) and not f(scripted[k]) for k in keys)
        lost_s = sum(not f(assisted[k]) and f(scripted[k]) for k in keys)
        for i, v in enumerate([n, *ok, won_s, lost_s]):
            totals[i] += v
        print(f"| {row} | {rate(ok[0], n)} | {rate(ok[1], n)} | {rate(ok[2], n)} | {won_a}, {lost_a} | "
              f"{won_s}, {lost_s}, {sign_test(won_s, lost_s):.2f} |")
    n = totals[0]
    print(f"| all {n} | {rate(totals[1], n)} | {rate(totals[2], n)} | {rate(totals[3], n)} | | "
          f"{totals[4]}, {totals[5]}, {sign_test(totals[4], totals[5]):.2f} |")


if __name__ == "__main__":
    main()
