#!/usr/bin/env python3
"""Summarise the aortic-arch runs of issue 35 item 5 (results/arch_wire).

Reads the `navigate --json` files arch_type{1,2,3}_{policy,scripted-omega,push-only}.json (and the
coronary-wire comparison arch_type1_policy_coronary014.json) beside this script, names each target
from the `navigate --list` tables targets_arch_typeK.txt (saved from the same mesh and centerline:
the target numbering differs between arch types) and prints Markdown tables: per arch x target x
controller successes/episodes, rate and Wilson 95 % interval, then outcome counts.

Usage: python3 results/arch_wire/summarize.py [> table.md]     (standard library only)
"""
import json
import math
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ARCHES = ["arch_type1", "arch_type2", "arch_type3"]
CONTROLLERS = ["policy", "scripted-omega", "push-only"]
OUTCOMES = ["success", "wrong_branch", "stuck", "timeout", "diverged"]


def wilson(k, n, z=1.959963984540054):
    """Wilson score interval for k successes in n trials (95 % by default)."""
    if n == 0:
        return (float("nan"), float("nan"))
    p = k / n
    d = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / d
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return (max(0.0, centre - half), min(1.0, centre + half))


def target_names(arch, folder=HERE):
    """Target id -> vessel name, from the navigate --list table (by the target's end radius)."""
    names = {}
    path = os.path.join(folder, f"targets_{arch}.txt")
    for line in open(path):
        m = re.match(r"\s*(\d+)\s+\(([^)]*)\)\s+([\d.]+)\s+([\d.]+)", line)
        if not m:
            continue
        tid, radius = int(m.group(1)), float(m.group(4))
        if radius > 10:
            name = "ascending aorta"
        elif radius > 5:
            name = "brachiocephalic"
        elif radius > 3.9:
            name = "left subclavian"
        else:
            name = "left common carotid"
        names[tid] = (name, float(m.group(3)))
    return names


def load(arch, controller, suffix=""):
    path = os.path.join(HERE, f"{arch}_{controller}{suffix}.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def per_target(data):
    """target id -> {outcome: count}."""
    table = {}
    for r in data["results"]:
        counts = table.setdefault(r["target"], {o: 0 for o in OUTCOMES})
        counts[r["outcome"]] = counts.get(r["outcome"], 0) + 1
    return table


def cell(counts):
    n = sum(counts.values())
    k = counts.get("success", 0)
    lo, hi = wilson(k, n)
    return f"{k}/{n} | {100 * k / n:.0f}% | {100 * lo:.0f}-{100 * hi:.0f}%"


def vessel_scale_section():
    """The same arches with --task-scale vessel (ARCH_CONTROLLER_vessel.json: 10 episodes per target, seeds 0-39
    in target order) beside the fixed (paper's) rules of the runs above (their own seeds: 50 or 25 per target)."""
    out = ["\n### Vessel-scale task beside the fixed rules (fixed: the runs above; vessel: 10 episodes per target)\n",
           "| arch | target | controller | fixed k/n | vessel k/n | vessel 95 % CI | vessel outcomes |",
           "|---|---|---|---|---|---|---|"]
    for a in ARCHES:
        names = target_names(a)
        for c in CONTROLLERS:
            vessel = load(a, c, "_vessel")
            if vessel is None:
                out.append(f"| {a} | | {c} | | missing | | |")
                continue
            fixed = load(a, c)
            for tid in sorted(names):
                v = [r for r in vessel["results"] if r["target"] == tid]
                f = [r for r in fixed["results"] if r["target"] == tid] if fixed else []
                kv = sum(r["outcome"] == "success" for r in v)
                kf = sum(r["outcome"] == "success" for r in f)
                lo, hi = wilson(kv, len(v))
                oc = ", ".join(f"{o} {n}" for o in OUTCOMES if (n := sum(r["outcome"] == o for r in v)) and o != "success")
                fixed_cell = f"{kf}/{len(f)}" if f else "missing"
                out.append(f"| {a} | {tid}: {names[tid][0]} | {c} | {fixed_cell} | {kv}/{len(v)} | "
                           f"{100 * lo:.0f}-{100 * hi:.0f}% | {oc} |")
    return out


def fifty_section():
    """fifty/: 50 episodes per target and controller with the vessel-scale task (the default for these inlets),
    the arches' centerlines extracted with the three bifurcations of the truth (2026-12-02), seeds 0-199 in
    target order; the target tables beside them (numbering as extracted)."""
    folder = os.path.join(HERE, "fifty")
    out = ["\n### 50 episodes per target, vessel-scale task (fifty/)\n",
           "| arch | target | " + " | ".join(f"{c} k/n | 95 % CI" for c in CONTROLLERS) + " |",
           "|---|---|" + "---|---|" * len(CONTROLLERS)]
    for a in ARCHES:
        names = target_names(a, folder)
        runs = {}
        for c in CONTROLLERS:
            path = os.path.join(folder, f"{a}_{c}.json")
            runs[c] = json.load(open(path)) if os.path.exists(path) and os.path.getsize(path) else None
        for tid in sorted(names):
            cells = []
            for c in CONTROLLERS:
                if runs[c] is None:
                    cells.append("not run | ")
                    continue
                rs = [r for r in runs[c]["results"] if r["target"] == tid]
                k = sum(r["outcome"] == "success" for r in rs)
                lo, hi = wilson(k, len(rs))
                cells.append(f"{k}/{len(rs)} | {100 * lo:.0f}-{100 * hi:.0f}%")
            out.append(f"| {a} | {tid}: {names[tid][0]} | " + " | ".join(cells) + " |")
    return out


def success_section(data):
    """In: the runs, {(arch, controller): navigate JSON or None}. Out: the lines of the success table per arch x
    target x controller (successes/episodes, rate, Wilson 95 %), each arch's all-targets row after its targets."""
    out = []
    out.append("### Success per arch x target x controller (successes/episodes | rate | Wilson 95 %)\n")
    header = "| arch | target (path mm) | " + " | ".join(f"{c} k/n | rate | 95 % CI" for c in CONTROLLERS) + " |"
    out.append(header)
    out.append("|" + "---|" * (2 + 3 * len(CONTROLLERS)))
    for a in ARCHES:
        names = target_names(a)
        tables = {c: per_target(data[(a, c)]) if data[(a, c)] else None for c in CONTROLLERS}
        for tid in sorted(names):
            name, path_mm = names[tid]
            cells = []
            for c in CONTROLLERS:
                t = tables[c]
                cells.append(cell(t[tid]) if t and tid in t else "missing | | ")
            out.append(f"| {a} | {tid}: {name} ({path_mm:.0f}) | " + " | ".join(cells) + " |")
        # all targets together
        cells = []
        for c in CONTROLLERS:
            d = data[(a, c)]
            cells.append(cell({"success": d["successes"], "other": d["episodes"] - d["successes"]})
                         if d else "missing | | ")
        out.append(f"| {a} | **all 4** | " + " | ".join(cells) + " |")
    return out


def outcome_section(data):
    """In: the runs, {(arch, controller): navigate JSON or None}. Out: the lines of the outcome-count table per arch x
    controller x target (with the folded wrong branches and the median simulated time)."""
    out = []
    out.append("\n### Outcome counts per arch x controller x target\n")
    out.append("| arch | controller | target | " + " | ".join(OUTCOMES) + " | wrong_branch folded | median sim s |")
    out.append("|" + "---|" * (3 + len(OUTCOMES) + 2))
    for a in ARCHES:
        names = target_names(a)
        for c in CONTROLLERS:
            d = data[(a, c)]
            if not d:
                out.append(f"| {a} | {c} | missing |" + " |" * (len(OUTCOMES) + 2))
                continue
            for tid in sorted(names):
                rs = [r for r in d["results"] if r["target"] == tid]
                counts = [sum(r["outcome"] == o for r in rs) for o in OUTCOMES]
                folded = sum(bool(r.get("folded")) for r in rs)
                times = sorted(r["sim_time_s"] for r in rs)
                med = times[len(times) // 2] if times else float("nan")
                out.append(f"| {a} | {c} | {tid}: {names[tid][0]} | " + " | ".join(map(str, counts))
                           + f" | {folded} | {med:.1f} |")
    return out


def wire_section(data, cmp_):
    """In: the runs and the coronary-wire run of arch_type1's policy (None: missing). Out: the lines of the wire
    comparison table (0.035" angled against 0.014" coronary, per target)."""
    out = []
    out.append("\n### Wire comparison, arch_type1, policy (same seeds 0..)\n")
    out.append("| wire | target | k/n | rate | 95 % CI | outcomes |")
    out.append("|---|---|---|---|---|---|")
    names = target_names("arch_type1")
    for label, d in [("0.035\" angled (aortic_035_angled.json)", data[("arch_type1", "policy")]),
                     ("0.014\" coronary (default)", cmp_)]:
        if not d:
            out.append(f"| {label} | missing | | | | |")
            continue
        for tid, counts in sorted(per_target(d).items()):
            oc = ", ".join(f"{o} {counts[o]}" for o in OUTCOMES[1:] if counts[o])
            out.append(f"| {label} | {tid}: {names[tid][0]} | {cell(counts)} | {oc} |")
    return out


def wall_time_section(data, cmp_):
    """In: the runs and the coronary-wire run (None: missing). Out: the lines listing each run's wall time."""
    out = []
    out.append("\n### Wall time per run (navigate's wall_time_s, one thread)\n")
    for a in ARCHES:
        for c in CONTROLLERS:
            d = data[(a, c)]
            if d:
                out.append(f"- {a} {c}: {d['episodes']} episodes, {d['wall_time_s']:.0f} s "
                           f"({d['wall_time_s'] / d['episodes']:.2f} s/episode)")
    if cmp_:
        out.append(f"- arch_type1 policy, coronary wire: {cmp_['episodes']} episodes, {cmp_['wall_time_s']:.0f} s")
    return out


def main():
    out = []
    missing = []
    data = {(a, c): load(a, c) for a in ARCHES for c in CONTROLLERS}
    for (a, c), d in data.items():
        if d is None:
            missing.append(f"{a}_{c}.json")
    out.extend(success_section(data))
    out.extend(outcome_section(data))
    cmp_ = load("arch_type1", "policy", "_coronary014")
    out.extend(wire_section(data, cmp_))
    if cmp_ is None:
        missing.append("arch_type1_policy_coronary014.json")
    out.extend(wall_time_section(data, cmp_))
    if missing:
        out.append("\nMissing runs: " + ", ".join(missing))
    out.extend(vessel_scale_section())
    out.extend(fifty_section())
    print("\n".join(out))
    return 0

if __name__ == "__main__":
    sys.exit(main())
