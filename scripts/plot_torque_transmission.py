"""Figure of the torque-transmission runs (issue 38 item 3).

Reads the JSON written by `torque-transmission --out F.json` and draws, per friction setting, the tip's
roll against the proximal roll over the full turn and back (a 1:1 line is perfect transmission), and
the lag (proximal - tip) over time. Usage:
  .venv/bin/python scripts/plot_torque_transmission.py results/torque_transmission/torque_transmission.json \
      results/torque_transmission/torque_transmission.png
"""
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src: str, dst: str) -> None:
    with open(src) as f:
        runs = json.load(f)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    colours = {0.0: "tab:blue", 0.05: "tab:orange", 0.1: "tab:red"}
    for r in runs:
        c = colours.get(round(r["mu"], 3), None)
        style = "-" if r["friction_torque"] else ":"
        label = f"mu = {r['mu']:g}, friction torque {'on' if r['friction_torque'] else 'off (paper)'}"
        prox = [math.degrees(v) for v in r["proximal_rad"]]
        tip = [math.degrees(v) for v in r["tip_rad"]]
        lag = [p - t for p, t in zip(prox, tip)]
        ax = axes[0] if r["friction_torque"] else axes[1]
        ax.plot(prox, tip, style, color=c, label=label)
        axes[2].plot(r["time_s"], lag, style, color=c, label=label)
    for ax, title in ((axes[0], "friction at the surface (friction_torque on)"),
                      (axes[1], "paper's model (friction on translations only)")):
        ax.plot([0, 360], [0, 360], color="0.7", lw=0.8, zorder=0)
        ax.set_xlabel("proximal roll [deg]")
        ax.set_ylabel("tip roll [deg]")
        ax.set_title(title, fontsize=10)
        ax.legend(fontsize=8)
    axes[2].axhline(0, color="0.7", lw=0.8)
    axes[2].set_xlabel("time [s] (full turn out in 2 s, back in 2 s)")
    axes[2].set_ylabel("lag, proximal - tip [deg]")
    axes[2].set_title("lag over time", fontsize=10)
    axes[2].legend(fontsize=7)
    fig.suptitle("Torque transmission through a 1.5 mm tube with three 90-degree bends (0.014 in wire)")
    fig.tight_layout()
    fig.savefig(dst, dpi=110)


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", help="the JSON torque-transmission --out wrote")
    parser.add_argument("png", help="the figure to write")
    args = parser.parse_args()
    try:
        main(args.runs, args.png)
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"error: {args.runs}: {e}")
