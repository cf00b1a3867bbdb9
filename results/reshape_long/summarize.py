"""Tables of results/reshape_long/README.md from the evaluate runs (standard library only).

push_pull/results.json: the shipped push/pull actor (act/2) with --recovery 3 --recovery-assist --reshape-tip 0.2
--reshape-tip-length 9 --force-limit 1.5; rotation/results.json: the scripted omega rule and the rotation-only SAC
actor with the recovery wrapper, --recovery 3 --reshape-tip 0.2 --reshape-tip-length 9 --force-limit 1.5. Both on
the two coronary rows, the table's 50 episodes (seeds 0-49).
Compared episode by episode with the same controllers and settings but the reshape of before (the tip bent to
0.3/mm over its own 6 mm): ../recovery_assist (the push/pull actor; coronary-like: the first 50 of its 200
episodes) and ../force_limit (the scripted rule: results.json and scripted_25/results.json; rotation-only SAC:
results.json, the first 25 episodes only). A row's episode k is the same at any episode scale.
Sign tests: exact two-sided binomial on the episodes where exactly one of the two succeeded, as the table's.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.dirname(HERE)
sys.path.insert(0, RESULTS)
from stats import rate, run_episodes, sign_test  # noqa: E402  (results/stats.py)

ROWS = ["coronary-like", "deformed coronary"]
ASSIST = {"coronary-like": "recovery_assist/coronary_like/results.json",
          "deformed coronary": "recovery_assist/deformed/results.json"}
# label, this run (file, column), the run with the 0.3/mm reshape (files, column)
CONTROLLERS = [
    ("push/pull SAC (act/2) + assist", ("push_pull/results.json", "sac-policy"), (None, "sac-policy")),
    ("scripted omega + wrapper", ("rotation/results.json", "scripted-omega"),
     (["force_limit/results.json", "force_limit/scripted_25/results.json"], "scripted-omega")),
    ("rotation SAC + wrapper", ("rotation/results.json", "sac-policy"), (["force_limit/results.json"], "sac-policy")),
]


def ok(e, stage):
    return (e if stage == "strict" else e[stage])["outcome"] == "success"


def before(row, files, column):
    out = {}
    for f in files or [ASSIST[row]]:
        out.update(run_episodes(os.path.join(RESULTS, f), row, column))
    return out


def main():
    print("| row | controller | strict | with recovery (K = 3) | with reshape (0.2/mm over 9 mm) | reshaped | "
          "pull-backs (mean) | peak node force, N (mean) | (largest) | peak node > 1.5 N | procedure time, s (mean) | "
          "same episodes with the 0.3/mm reshape | long against 0.3/mm: won, lost (p) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    runs = {}
    for row in ROWS:
        for label, (path, column), (files, old_column) in CONTROLLERS:
            eps = run_episodes(os.path.join(HERE, path), row, column)
            if not eps:
                continue
            runs[(row, label)] = eps
            keys = sorted(eps)
            n = len(keys)
            cells = " | ".join(rate(sum(ok(eps[k], s) for k in keys), n) for s in ("strict", "recovery", "reshape"))
            sh = [eps[k]["reshape"] for k in keys]
            peaks = [r.get("force", {}).get("peak_node_N", 0.0) for r in sh]
            old = before(row, files, old_column)
            common = [k for k in keys if k in old]
            won = sum(ok(eps[k], "reshape") and not ok(old[k], "reshape") for k in common)
            lost = sum(ok(old[k], "reshape") and not ok(eps[k], "reshape") for k in common)
            print(f"| {row} | {label} | {cells} | {sum(r['reshaped'] for r in sh)} | "
                  f"{sum(r['attempts'] for r in sh) / n:.2f} | {sum(peaks) / n:.2f} | {max(peaks):.2f} | "
                  f"{sum(p > 1.5 for p in peaks)}/{n} | {sum(r['procedure_time_s'] for r in sh) / n:.1f} | "
                  f"{rate(sum(ok(old[k], 'reshape') for k in common), len(common)) if common else '-'} | "
                  f"{won}, {lost} ({sign_test(won, lost):.3f}) |")
    print()
    print("| row | comparison (with reshape, same episodes) | won | lost | p (sign test) |")
    print("|---|---|---|---|---|")
    for row in ROWS:
        a, a_label = runs.get((row, CONTROLLERS[0][0])), CONTROLLERS[0][0]
        for b_label in (CONTROLLERS[1][0], CONTROLLERS[2][0]):
            b = runs.get((row, b_label))
            if not a or not b:
                continue
            keys = [k for k in a if k in b]
            won = sum(ok(a[k], "reshape") and not ok(b[k], "reshape") for k in keys)
            lost = sum(ok(b[k], "reshape") and not ok(a[k], "reshape") for k in keys)
            print(f"| {row} | {a_label} against {b_label} | {won} | {lost} | {sign_test(won, lost):.3f} |")
    print()
    print("| row | controller | episodes not reached (anatomy T target seed: the procedure's end) |")
    print("|---|---|---|")
    for (row, label), eps in runs.items():
        lost = [f"{k[0]} T{k[1]} s{k[2]}: {eps[k]['reshape']['outcome']}" for k in sorted(eps)
                if not ok(eps[k], "reshape")]
        print(f"| {row} | {label} | {', '.join(lost) or 'none'} |")


if __name__ == "__main__":
    main()
