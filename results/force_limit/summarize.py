"""Tables of results/force_limit/README.md from the evaluate runs beside this file (standard library only).

results.json: the scripted omega rule and the shipped rotation-only SAC, each with the recovery wrapper (--recovery 3),
the tip reshape (--reshape-tip 0.3) and the force limit (--force-limit 1.5); push_pull/results.json: the shipped
push/pull actor (act/2) the same way. Each is compared, episode by episode, with the same command without the limit:
../reshape/results.json and ../reshape/push_pull/results.json (the first 25 episodes of the coronary-like and
deformed coronary rows, seeds 0-24).
push_pull_25/, scripted_25/: episodes 25-49 of the same rows (`--episode-scale 1 --episodes 25:25`), the push/pull
actor and the scripted rule with everything on; with the first 25 they are the rows' 50 episodes (a row's episode k
is the same at any episode scale), for the push/pull actor against the scripted rule (issue 37 item 3).
push_pull_50/, scripted_50/: episodes 50-199 of the coronary-like row (`--episode-scale 4 --episodes 50:150`), the same
two, run after the first 50 left that row undecided: with them it is the row's 200 episodes.
Sign tests: exact two-sided binomial on the episodes where exactly one of the two succeeded, as the table's.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from stats import rate, run_episodes, sign_test  # noqa: E402  (results/stats.py)

ROWS = ["coronary-like", "deformed coronary"]
# (label, file beside this one, the run without the limit, column)
CONTROLLERS = [
    ("scripted omega + wrapper", "results.json", "../reshape/results.json", "scripted-omega"),
    ("shipped SAC (act/1) + wrapper", "results.json", "../reshape/results.json", "sac-policy"),
    ("push/pull SAC (act/2)", "push_pull/results.json", "../reshape/push_pull/results.json", "sac-policy"),
]
STAGES = [("strict", lambda e: e["outcome"]), ("with recovery", lambda e: e["recovery"]["outcome"]),
          ("with reshape", lambda e: e["reshape"]["outcome"])]


def episodes(path, row, column):
    return run_episodes(os.path.join(HERE, path), row, column)


def force_cells(eps):
    f = [e["reshape"]["force"] for e in eps.values() if "force" in e["reshape"]]
    peaks = [x["peak_node_N"] for x in f]
    n = len(eps)
    return (f"{sum(peaks) / max(1, len(peaks)):.2f} | {max(peaks):.2f} | {sum(p > 1.5 for p in peaks)}/{len(peaks)} | "
            f"{sum(x.get('push_held_s', 0.0) for x in f) / max(1, len(f)):.2f} | "
            f"{sum(e['reshape']['procedure_time_s'] for e in eps.values()) / n:.1f}")


def main():
    print("| row | controller | force limit | strict | with recovery (K = 3) | with reshape (tip 0.3/mm) | "
          "peak node force, N (mean) | (largest) | episodes with peak node > 1.5 N | backed off, s (mean) | "
          "procedure time, s (mean) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    pairs = {}
    for row in ROWS:
        for label, path, before_path, column in CONTROLLERS:
            now, before = episodes(path, row, column), episodes(before_path, row, column)
            if not now or not before:
                continue
            before = {k: before[k] for k in now if k in before}
            pairs[(row, label)] = (before, now)
            for name, eps in (("off", before), ("1.5 N", now)):
                n = len(eps)
                cells = " | ".join(rate(sum(f(e) == "success" for e in eps.values()), n) for _, f in STAGES)
                print(f"| {row} | {label} | {name} | {cells} | {force_cells(eps)} |")

    print("\n| row | controller | stage | won with the limit | lost with it | p (sign test) |")
    print("|---|---|---|---|---|---|")
    for (row, label), (before, now) in pairs.items():
        for stage, f in STAGES:
            won = sum(f(now[k]) == "success" and f(before[k]) != "success" for k in now)
            lost = sum(f(now[k]) != "success" and f(before[k]) == "success" for k in now)
            print(f"| {row} | {label} | {stage} | {won} | {lost} | {sign_test(won, lost):.3f} |")

    print("\nEpisodes whose procedure (with reshape) ended otherwise, or whose peak node force changed by over 0.3 N:\n")
    for (row, label), (before, now) in pairs.items():
        for key in sorted(now):
            a, b = before[key]["reshape"], now[key]["reshape"]
            pa, pb = a.get("force", {}).get("peak_node_N", 0.0), b.get("force", {}).get("peak_node_N", 0.0)
            if a["outcome"] != b["outcome"] or abs(pa - pb) > 0.3:
                print(f"- {row}, {label}: {key[0]} T{key[1]} seed {key[2]}: {a['outcome']} at {pa:.2f} N -> "
                      f"{b['outcome']} at {pb:.2f} N (backed off {b.get('force', {}).get('push_held_s', 0.0):.2f} s)")

    print("\nThe push/pull actor against the scripted rule, both with recovery, reshape and the limit, on the rows' "
          "first 50 episodes (seeds 0-49), and on the coronary-like row's 200 (seeds 0-199):\n")
    print("| row | stage | push/pull SAC (act/2) | scripted omega + wrapper | won | lost | p (sign test) | "
          "peak node > 1.5 N (push/pull, scripted) |")
    print("|---|---|---|---|---|---|---|---|")
    for row, more in [(r, False) for r in ROWS] + [("coronary-like", True)]:
        pp = {**episodes("push_pull/results.json", row, "sac-policy"), **episodes("push_pull_25/results.json", row, "sac-policy")}
        sc = {**episodes("results.json", row, "scripted-omega"), **episodes("scripted_25/results.json", row, "scripted-omega")}
        if more:
            pp.update(episodes("push_pull_50/results.json", row, "sac-policy"))
            sc.update(episodes("scripted_50/results.json", row, "scripted-omega"))
        keys = [k for k in pp if k in sc]
        if len(keys) < (200 if more else 50):
            continue
        n = len(keys)
        for stage, f in STAGES:
            won = sum(f(pp[k]) == "success" and f(sc[k]) != "success" for k in keys)
            lost = sum(f(pp[k]) != "success" and f(sc[k]) == "success" for k in keys)
            over = [sum(d[k]["reshape"].get("force", {}).get("peak_node_N", 0.0) > 1.5 for k in keys) for d in (pp, sc)]
            print(f"| {row}{', 200 episodes' if more else ''} | {stage} | {rate(sum(f(pp[k]) == 'success' for k in keys), n)} | "
                  f"{rate(sum(f(sc[k]) == 'success' for k in keys), n)} | {won} | {lost} | {sign_test(won, lost):.3f} | "
                  f"{over[0]}/{n}, {over[1]}/{n} |")


if __name__ == "__main__":
    main()
