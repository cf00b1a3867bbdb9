"""Tables of results/junctions/README.md from the evaluate runs beside this file (standard library only).

separate/, separate_close/: `evaluate --rows ...` with the paper's junction reading (every controller, ceiling);
combined/, combined_close/: the same rows and seeds with `--junctions combined` (the controllers that read omega);
separate_outer_50/: the corrected pair, paper's reading; kway_outer/: its trifurcation row with `--junctions kway`;
obs6_outer/, obs6_table/: the obs/6 actor trained with the k-way patterns on the corrected pair and on the table's
rows the shipped actor fills (compared with results/results.json's SAC column, same episodes);
gap_outer/: the corrected trifurcation row with the widest-gap reading (commit 983e190, reverted), against kway_outer/.
"""
import json
import os
import sys
from collections import Counter, defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from stats import sign_test, wilson  # noqa: E402  (results/stats.py)

COLUMNS = ["sac-policy", "scripted-omega", "scripted-omega-ccw", "push-only"]


def rows(*folders):
    out = {}
    for f in folders:
        path = os.path.join(HERE, f, "results.json")
        if os.path.exists(path):
            for r in json.load(open(path))["rows"]:
                out[r["name"]] = r
    return out


def cell(summary):
    k, n = summary["successes"], summary["episodes"]
    lo, hi = wilson(k, n)
    return f"{k}/{n} ({100 * k / n:.0f}%, {100 * lo:.0f}-{100 * hi:.0f}%)"


def by_episode(summary):
    return {(e["anatomy"], e["target"], e["seed"]): e["outcome"] == "success" for e in summary["results"]}


def table_row(name, label, r):
    """One row of the success table: every column's rate (push-only only in the paper's reading) and the ceiling."""
    cells = [cell(r["results"][c]) if c in r["results"] else "same as separate (no omega)" for c in COLUMNS]
    ceiling = r.get("ceiling")
    ceil = f"{ceiling['reached']}/{ceiling['episodes']}" if ceiling else "—"
    return f"| {name} | {label} | " + " | ".join(cells) + f" | {ceil} |"


def won_lost(paper, other):
    """Episodes reached only with `other`'s reading, and only with the paper's."""
    a, b = by_episode(paper), by_episode(other)
    return sum(1 for k in a if b.get(k) and not a[k]), sum(1 for k in a if a[k] and not b.get(k))


separate, combined = rows("separate", "separate_close"), rows("combined", "combined_close")
print("| row | junctions | " + " | ".join(COLUMNS) + " | reached by a controller or rotation schedule |")
print("|---|---|" + "---|" * (len(COLUMNS) + 1))
for name in ["trifurcation tree", "closely spaced forks"]:
    for label, table in (("separate (paper)", separate), ("combined", combined)):
        r = table.get(name)
        if r is None:
            print(f"| {name} | {label} | " + " | ".join("not run" for _ in COLUMNS) + " | |")
            continue
        print(table_row(name, label, r))

print("\nSame episodes, combined against separate (won: reached only with combined; lost: only with separate; exact sign test):\n")
print("| row | column | won | lost | p |")
print("|---|---|---|---|---|")
for name in ["trifurcation tree", "closely spaced forks"]:
    if name not in separate or name not in combined:
        continue
    for c in COLUMNS[:3]:
        if c not in combined[name]["results"]:
            continue
        won, lost = won_lost(separate[name]["results"][c], combined[name]["results"][c])
        print(f"| {name} | {c} | {won} | {lost} | {sign_test(won, lost):.2f} |")

print("\nPer target (SAC, successes/episodes; outcomes of the losses):\n")
print("| row | target | separate | combined |")
print("|---|---|---|---|")
for name in ["trifurcation tree", "closely spaced forks"]:
    per = defaultdict(dict)
    for label, table in (("separate", separate), ("combined", combined)):
        if name not in table:
            continue
        eps = table[name]["results"]["sac-policy"]["results"]
        for t in sorted({e["target"] for e in eps}):
            mine = [e for e in eps if e["target"] == t]
            k = sum(e["outcome"] == "success" for e in mine)
            losses = Counter(e["outcome"] for e in mine if e["outcome"] != "success")
            per[t][label] = f"{k}/{len(mine)}" + (" (" + ", ".join(f"{o} {n}" for o, n in losses.items()) + ")" if losses else "")
    for t in sorted(per):
        print(f"| {name} | T{t} | {per[t].get('separate', '')} | {per[t].get('combined', '')} |")


print("\nThe corrected trifurcation tree, k-way junctions read together (`--junctions kway`) against the paper's reading, "
      "same 50 episodes:\n")
outer, kway = rows("separate_outer_50"), rows("kway_outer")
name = "trifurcation tree (outer side branches)"
if name in outer and name in kway:
    print("| row | junctions | " + " | ".join(COLUMNS) + " | reached by a controller or rotation schedule |")
    print("|---|---|" + "---|" * (len(COLUMNS) + 1))
    for label, table in (("separate (paper)", outer), ("kway", kway)):
        print(table_row(name, label, table[name]))
    print("\n| column | won (kway only) | lost (separate only) | p |")
    print("|---|---|---|---|")
    for c in COLUMNS[:3]:
        won, lost = won_lost(outer[name]["results"][c], kway[name]["results"][c])
        print(f"| {c} | {won} | {lost} | {sign_test(won, lost):.3f} |")
    print("\n| target | SAC separate | SAC kway |")
    print("|---|---|---|")
    for t in sorted({e["target"] for e in kway[name]["results"]["sac-policy"]["results"]}):
        cells = []
        for table in (outer, kway):
            mine = [e for e in table[name]["results"]["sac-policy"]["results"] if e["target"] == t]
            cells.append(f"{sum(e['outcome'] == 'success' for e in mine)}/{len(mine)}")
        print(f"| T{t} | " + " | ".join(cells) + " |")


print("\nAn actor trained with k-way junctions (obs/6, `runs/obs6_kway`), zero-shot on the corrected pair, against the "
      "shipped obs/3 actor on the same 50 episodes (trifurcation: with kway; close forks: kway = the paper's reading):\n")
obs6 = rows("obs6_outer")
shipped = {"trifurcation tree (outer side branches)": kway.get("trifurcation tree (outer side branches)"),
           "closely spaced forks (outer side branches)": outer.get("closely spaced forks (outer side branches)")}
print("| row | shipped obs/3 SAC | obs/6 SAC | won | lost | p | reached by a controller or rotation schedule |")
print("|---|---|---|---|---|---|---|")
for name, before in shipped.items():
    if name not in obs6 or before is None:
        continue
    a, b = before["results"]["sac-policy"], obs6[name]["results"]["sac-policy"]
    won, lost = won_lost(a, b)
    ceiling = outer[name].get("ceiling")
    print(f"| {name} | {cell(a)} | {cell(b)} | {won} | {lost} | {sign_test(won, lost):.3f} | "
          f"{ceiling['reached']}/{ceiling['episodes']} |")

obs6_table = rows("obs6_table")
if obs6_table:
    table = rows("..")  # results/results.json, the shipped table
    print("\nThe results table's rows the shipped actor fills, same episodes (shipped obs/3 SAC from results/results.json):\n")
    print("| row | shipped obs/3 SAC | obs/6 SAC | won | lost | p |")
    print("|---|---|---|---|---|---|")
    total = [0, 0, 0, 0]
    for name, r in obs6_table.items():
        a, b = table[name]["results"]["sac-policy"], r["results"]["sac-policy"]
        won, lost = won_lost(a, b)
        total = [total[0] + a["successes"], total[1] + b["successes"], total[2] + won, total[3] + lost]
        print(f"| {name} | {cell(a)} | {cell(b)} | {won} | {lost} | {sign_test(won, lost):.3f} |")
    print(f"| all | {total[0]} | {total[1]} | {total[2]} | {total[3]} | {sign_test(total[2], total[3]):.3f} |")

gap = rows("gap_outer")
name = "trifurcation tree (outer side branches)"
if name in gap and name in kway:
    print("\nThe widest-gap reading (commit 983e190, reverted) against kway on the corrected trifurcation tree, "
          "episodes with the same outcome, steps and simulated time:\n")
    for c in COLUMNS[:3]:
        key = lambda e: (e["target"], e["seed"])
        a = {key(e): (e["outcome"], e["steps"], e["sim_time_s"]) for e in kway[name]["results"][c]["results"]}
        b = {key(e): (e["outcome"], e["steps"], e["sim_time_s"]) for e in gap[name]["results"][c]["results"]}
        print(f"- {c}: {sum(a.get(k) == v for k, v in b.items())} of {len(b)} ({cell(gap[name]['results'][c])})")
