"""Speed of friction with a lever arm (issue 38 item 5): the same benchmarks with friction_torque off
(the paper's model, the code path of before) and on, interleaved in one run so that both see the same
machine load, N times each; writes every run and the medians as JSON.

  .venv/bin/python scripts/bench_friction_torque.py --build build --repeats 3 \
      --out results/torque_transmission/speed.json

Benchmarks: `bench-mechanics` (100 mm insertion into the coronary tree at 20 mm/s, push only) and
`torque-transmission --mu 0.1 --turn-seconds 0.5` (a full turn and back in the three-bend tube, where
the wall's friction turns the wire). Wall-clock figures of a shared machine: read the medians.
"""
import argparse
import json
import platform
import statistics
import subprocess
import time


def run(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    runs = {"off": {"insertion": [], "tube": []}, "on": {"insertion": [], "tube": []}}
    for _ in range(a.repeats):
        for tag in ("off", "on"):
            cmd = [f"{a.build}/apps/bench-mechanics", "--scaling-substeps", "200"]
            if tag == "on":
                cmd.append("--friction-torque")
            d = run(cmd)
            ins = d["insertion"]
            runs[tag]["insertion"].append({k: ins[k] for k in (
                "ok", "substeps_per_s", "mean_contacts", "mean_max_pgs_sweeps", "split_substeps",
                "us_per_substep_by_stage", "tip", "max_penetration_mm")})
            t = run([f"{a.build}/apps/torque-transmission", "--mu", "0.1", "--turn-seconds", "0.5",
                     "--friction-torque", tag])[0]
            runs[tag]["tube"].append({k: t[k] for k in (
                "ok", "substeps_per_s", "mean_contacts", "mean_max_pgs_sweeps", "split_substeps",
                "us_per_substep_by_stage", "max_lag_rad")})
    summary = {}
    for bench in ("insertion", "tube"):
        med = {tag: statistics.median(r["substeps_per_s"] for r in runs[tag][bench]) for tag in ("off", "on")}
        con = {tag: statistics.median(r["us_per_substep_by_stage"]["constraints_us"] for r in runs[tag][bench])
               for tag in ("off", "on")}
        summary[bench] = {
            "substeps_per_s_median_off": med["off"],
            "substeps_per_s_median_on": med["on"],
            "on_vs_off": med["on"] / med["off"] - 1.0,
            "constraints_us_median_off": con["off"],
            "constraints_us_median_on": con["on"],
        }
    doc = {
        "measured": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "machine": f"{platform.node()} ({platform.machine()}), shared with other jobs",
        "repeats": a.repeats,
        "summary": summary,
        "runs": runs,
    }
    with open(a.out, "w") as f:
        json.dump(doc, f, indent=1)
    print(json.dumps(summary, indent=1))


if __name__ == "__main__":
    main()
