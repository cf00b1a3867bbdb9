"""The results table on a Ray cluster (issue 40): `evaluate`'s episodes as Ray tasks, joined into the
same results.json and results.md as one machine running `evaluate` with the same flags.

    python -m guidewire_nav.cluster evaluate --out results/ --episode-scale 0.1     # local Ray, all cores
    python -m guidewire_nav.cluster evaluate --address auto --out results/          # a running cluster
    python -m guidewire_nav.cluster bench --rows var1 --episode-scale 0.2 --threads 2  # Ray's overhead, JSON

How: `evaluate --plan` names the rows the flags select and their episode counts; each row is cut into
shards of --shard-episodes episodes, and each shard is a Ray task running the C++ `evaluate --rows <row>
--episodes FIRST:COUNT` with every other flag as given. A row's shards are joined in episode order by
`evaluate --from-json` (shards of one run join into that run: same settings, same episodes, outcomes
and steps), the rows in the table's order, and `evaluate --from-json` writes results.md from the
joined results.json. Nothing here computes a figure of the table. A task whose worker dies (or whose
evaluate is killed) is run again by Ray (--max-retries); each shard's result is kept once, under its
episode range, and the join refuses an episode twice. Every node runs the same executable and reads
the same files (policy, anatomies) by the same paths: a shared or identical checkout (docs/cluster.md).
Finished shards are kept in <out>/shards/<flags hash>/, so --resume runs only the missing ones.
"""

import argparse
import ctypes
import hashlib
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import guidewire_nav

class ShardLost(RuntimeError):
    """evaluate died of a signal (killed with its node, out of memory): Ray runs the shard again."""


# evaluate's flags this tool handles itself (--out, --rows, --resume, --threads: below) or refuses (a shard's
# own, or running nothing); every other flag `evaluate --help` lists is offered and passed to each shard.
OWN_FLAGS = {"--help", "--out", "--rows", "--resume", "--threads", "--from-json", "--episodes", "--plan"}
# A CLI11 option line of `evaluate --help`: "  --seed UINT   episode k ...", "  --resume   keep ...".
OPTION_LINE = re.compile(r"^  (?:-\w,)?(--[\w-]+)(?: ([A-Z][A-Z:]*)(?:=\S+)?( \.\.\.)?)?(?:\s+(\S.*))?$")


def evaluate_flags(evaluate: Path):
    """[(flag, takes a value, several values, help)] from `evaluate --help` ([] when it is not built)."""
    try:
        text = subprocess.run([str(evaluate), "--help"], capture_output=True, text=True, timeout=60).stdout
    except OSError:
        return []
    flags, lines = [], text.splitlines() + [""]
    for line, after in zip(lines, lines[1:]):
        m = OPTION_LINE.match(line)
        if m and m.group(1) not in OWN_FLAGS:  # a long option's help starts on the next line
            # CLI11 puts its own notes after the type ("Needs: --x", "in [0 - 360]", "Excludes: --y"); the help proper
            # is then on the next line, and the note follows it.
            note = m.group(4) if m.group(4) and re.match(r"(Needs|Excludes|in \[|\[)", m.group(4)) else None
            own = m.group(4) if m.group(4) and not note else None
            help_text = own or (after.strip() if after.startswith("    ") else m.group(1))
            if note:
                help_text = f"{help_text} ({note})"
            flags.append((m.group(1), m.group(2) is not None, m.group(3) is not None, help_text))
    return flags


def parse_args(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    # The executable first: its --help says which flags there are to pass on.
    pre = argparse.ArgumentParser(add_help=False, allow_abbrev=False)
    pre.add_argument("--evaluate", type=Path, default=guidewire_nav.app_path("evaluate"))
    evaluate = pre.parse_known_args(argv)[0].evaluate
    passed = evaluate_flags(evaluate)

    parser = argparse.ArgumentParser(
        prog="gw-cluster", description=__doc__.split("\n\n")[0], allow_abbrev=False,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, help="what to run")
    for name, text in (("evaluate", "the results table as Ray tasks, joined as one machine's run"),
                       ("bench", "episodes per second: one machine `evaluate --threads N` against the Ray "
                                 "path with N CPUs, as JSON")):
        p = sub.add_parser(name, help=text, description=text, allow_abbrev=False)
        p.add_argument("--address", default=None,
                       help="Ray cluster to join ('auto': the one `ray start` runs on this machine, or "
                            "HOST:PORT); default: start a local Ray on this machine")
        p.add_argument("--cpus", type=int, default=None,
                       help="local Ray only: CPUs it may use (default: all of this machine's)")
        p.add_argument("--evaluate", type=Path, default=evaluate,
                       help="the C++ evaluate executable, by the same path on every node "
                            "(default: $GW_BUILD_DIR or build/, apps/evaluate)")
        p.add_argument("--shard-episodes", type=int, default=10,
                       help="episodes of a row in one Ray task (each column runs them; a smaller shard spreads "
                            "better, each costs a start and the row's anatomy loading)")
        p.add_argument("--max-retries", type=int, default=3,
                       help="times Ray runs a shard again whose worker or evaluate died")
        p.add_argument("--threads", type=int, default=1,
                       help="evaluate's --threads inside each task, and the CPUs each task reserves (bench: the "
                            "one-machine run's threads and the Ray run's CPUs)")
        p.add_argument("--out", type=Path, default=Path("results") if name == "evaluate" else None,
                       help="folder for results.md and results.json (evaluate's --out), and shards/"
                            + ("" if name == "evaluate" else "; bench: both runs' tables (default: a temporary "
                               "folder)"))
        p.add_argument("--rows", default="",
                       help="only rows whose name contains one of these comma-separated texts (evaluate's --rows)")
        p.add_argument("--resume", action="store_true",
                       help="keep the shards an earlier run with the same flags finished (<out>/shards/) and run "
                            "only the others")
        group = p.add_argument_group("evaluate's flags (`evaluate --help`), passed to every shard unchanged")
        for flag, value, several, help_text in passed:
            if several:
                group.add_argument(flag, nargs="+", default=None, help=help_text.replace("%", "%%"))
            elif value:
                group.add_argument(flag, default=None, help=help_text.replace("%", "%%"))
            else:
                group.add_argument(flag, action="store_true", help=help_text.replace("%", "%%"))
    sub.choices["bench"].add_argument("--json", type=Path, default=None,
                                      help="also write the JSON to this file (e.g. results/cluster/bench.json)")
    args = parser.parse_args(argv)
    args.passthrough = []
    for flag, value, several, _ in passed:
        given = getattr(args, flag[2:].replace("-", "_"))
        if several and given:
            args.passthrough += [flag, *given]
        elif value and given is not None:
            args.passthrough += [flag, given]
        elif not value and given:
            args.passthrough.append(flag)
    return args


def run_evaluate(command, cwd=None):
    """evaluate's stdout; raises with its stderr when it fails."""
    done = subprocess.run(command, capture_output=True, text=True, cwd=cwd)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, command))} failed ({done.returncode}):\n{done.stderr[-3000:]}")
    return done.stdout


def plan_rows(args):
    """[(name, episodes, --rows text that selects this row alone)] in the table's order."""
    base = [str(args.evaluate), "--plan", *args.passthrough]
    table = [r["name"] for r in json.loads(run_evaluate(base))["rows"]]
    chosen = json.loads(run_evaluate(base + (["--rows", args.rows] if args.rows else [])))["rows"]
    planned = []
    for row in chosen:
        # --rows matches a comma-separated text anywhere in a name: the longest piece of this name that no
        # other row's name contains picks it alone.
        pieces = sorted((p.strip() for p in row["name"].split(",") if p.strip()), key=len, reverse=True)
        alone = [p for p in pieces if sum(p in other for other in table) == 1]
        if not alone:
            raise RuntimeError(f"no --rows text selects row '{row['name']}' alone")
        planned.append((row["name"], row["episodes"], alone[0]))
    return planned


def shards_of(planned, per_shard):
    """[(row, first, count, rows_text)]: every row cut in episode order; a row of one shard runs whole."""
    out = []
    for name, episodes, text in planned:
        n = max(1, math.ceil(episodes / per_shard))
        size = math.ceil(episodes / n)  # even shards: 50 episodes by 10 -> 5 x 10, by 15 -> 4 x 13
        for first in range(0, episodes, size):
            out.append((name, first, min(size, episodes - first), text))
    return out


def die_with_parent():
    """In the evaluate child: killed when the Ray worker that started it dies (Linux)."""
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


def run_shard(evaluate, cwd, flags, row_text, first, count, whole, threads):
    """One shard on whatever node Ray chose: evaluate into a fresh folder; returns its results.json text.
    The caller's folder when this node has it (relative paths in the flags mean the same), else /tmp."""
    with tempfile.TemporaryDirectory(prefix="gw-shard-") as out:
        command = [evaluate, *flags, "--rows", row_text, "--threads", str(threads), "--out", out]
        if not whole:
            command += ["--episodes", f"{first}:{count}"]
        done = subprocess.run(command, capture_output=True, text=True, preexec_fn=die_with_parent,
                              cwd=cwd if os.path.isdir(cwd) else None)
        if done.returncode < 0:
            raise ShardLost(f"evaluate killed by signal {-done.returncode}")
        if done.returncode != 0:
            raise RuntimeError(f"evaluate failed ({done.returncode}): {done.stderr[-3000:]}")
        return Path(out, "results.json").read_text()


def start_ray(args):
    import ray  # the [cluster] extra: pip install -e "training[cluster]"

    if args.address:
        ray.init(address=args.address, log_to_driver=False)
    else:
        ray.init(num_cpus=args.cpus, include_dashboard=False, log_to_driver=False,
                 object_store_memory=200 * 1024 * 1024)
    return ray


def shard_file(folder, row, first):
    slug = hashlib.sha256(row.encode()).hexdigest()[:10]
    return folder / f"{slug}-{first:06d}.json"


def join_row(args, row, files, scratch):
    """The row from its shards' results.json files (episode order): evaluate --from-json joins them."""
    if len(files) == 1:
        result = json.loads(files[0].read_text())
    else:
        run_evaluate([str(args.evaluate), "--from-json", *map(str, files), "--out", str(scratch)])
        result = json.loads((scratch / "results.json").read_text())
    rows = [r for r in result["rows"] if r["name"] == row]
    if len(rows) != 1:
        raise RuntimeError(f"the shards of row '{row}' hold {len(rows)} such rows")
    settings = dict(result["settings"])
    settings.pop("episodes", None)  # a whole row run as one shard never had it
    return rows[0], settings


def write_table(args, rows, settings):
    """results.json as evaluate writes it, then results.md from it by evaluate --from-json."""
    args.out.mkdir(parents=True, exist_ok=True)
    tmp = args.out / "results.json.tmp"
    tmp.write_text(json.dumps({"rows": rows, "settings": settings}, indent=2) + "\n")
    tmp.replace(args.out / "results.json")
    return run_evaluate([str(args.evaluate), "--from-json", str(args.out / "results.json"), "--out", str(args.out)])


def evaluate_on_ray(args):
    """Runs the table as shards on Ray; returns {episodes, shards, shards_run (the others were kept from an earlier
    run), wall_s, markdown}."""
    started = time.monotonic()
    planned = plan_rows(args)
    shards = shards_of(planned, max(1, args.shard_episodes))
    key = hashlib.sha256(json.dumps([str(args.evaluate), args.passthrough]).encode()).hexdigest()[:12]
    folder = args.out / "shards" / key
    if folder.exists() and not args.resume:
        shutil.rmtree(folder)
    folder.mkdir(parents=True, exist_ok=True)
    whole = {name: sum(1 for s in shards if s[0] == name) == 1 for name, _, _ in planned}
    todo = [s for s in shards if not shard_file(folder, s[0], s[1]).is_file()]
    print(f"[cluster] {len(planned)} row(s), {len(shards)} shard(s), {len(shards) - len(todo)} kept; "
          f"shards in {folder}", file=sys.stderr)

    ray = start_ray(args)
    print(f"[cluster] Ray: {ray.cluster_resources().get('CPU', 0):.0f} CPU(s)", file=sys.stderr)
    task = ray.remote(num_cpus=args.threads, max_retries=args.max_retries,
                      retry_exceptions=[ShardLost])(run_shard)
    pending = {task.remote(str(args.evaluate.resolve()), os.getcwd(), args.passthrough, text, first, count,
                           whole[name], args.threads): (name, first) for name, first, count, text in todo}
    rows, settings, joined = {}, None, set()
    scratch = Path(tempfile.mkdtemp(prefix="gw-join-"))
    try:
        while True:
            # Rows whose shards are all in, joined and written in the table's order (an interruption
            # loses no finished row, as with evaluate).
            for name, _, _ in planned:
                files = [shard_file(folder, s[0], s[1]) for s in shards if s[0] == name]
                if name not in joined and all(f.is_file() for f in files):
                    rows[name], settings = join_row(args, name, files, scratch)
                    joined.add(name)
                    write_table(args, [rows[n] for n, _, _ in planned if n in rows], settings)
                    print(f"[cluster] row {name}: done", file=sys.stderr)
            if not pending:
                break
            ready, _ = ray.wait(list(pending), num_returns=1)
            name, first = pending.pop(ready[0])
            text = ray.get(ready[0])  # a shard that failed for good raises here, naming evaluate's error
            path = shard_file(folder, name, first)
            path.with_suffix(".tmp").write_text(text)
            path.with_suffix(".tmp").replace(path)
            print(f"[cluster] shard {name} from episode {first}: in ({len(pending)} running or queued)",
                  file=sys.stderr)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
        ray.shutdown()
    md = write_table(args, [rows[n] for n, _, _ in planned], settings)
    episodes = sum(col["episodes"] for r in rows.values() for col in r.get("results", {}).values())
    return {"episodes": episodes, "shards": len(shards), "shards_run": len(todo), "wall_s": time.monotonic() - started,
            "markdown": md}


def bench(args):
    """One machine's evaluate --threads N and the Ray path with N CPUs on the same flags: episodes/s."""
    threads = args.threads
    if args.out is None:
        args.out = Path(tempfile.mkdtemp(prefix="gw-bench-"))
    load_before = os.getloadavg()[0]  # other work on the machine skews both figures
    one_out = args.out / "one-machine"
    command = [str(args.evaluate), *args.passthrough, "--threads", str(threads), "--out", str(one_out)]
    if args.rows:
        command += ["--rows", args.rows]
    started = time.monotonic()
    run_evaluate(command)
    one_wall = time.monotonic() - started
    one = json.loads((one_out / "results.json").read_text())
    one_episodes = sum(c["episodes"] for r in one["rows"] for c in r.get("results", {}).values())

    ray_args = argparse.Namespace(**vars(args))
    ray_args.out, ray_args.threads, ray_args.resume = args.out / "ray", 1, False
    ray_args.cpus = args.cpus or threads
    ray_run = evaluate_on_ray(ray_args)
    same = strip_wall_times(json.loads((ray_args.out / "results.json").read_text())) == strip_wall_times(one)
    report = {
        "host_cpus": os.cpu_count(),
        "load_average_1min": {"before": round(load_before, 2), "after": round(os.getloadavg()[0], 2)},
        "flags": args.passthrough + (["--rows", args.rows] if args.rows else []),
        "episodes": one_episodes,
        "one_machine": {"command": f"evaluate --threads {threads}", "wall_s": round(one_wall, 2),
                        "episodes_per_s": round(one_episodes / one_wall, 4)},
        "ray": {"command": f"gw-cluster evaluate --cpus {ray_args.cpus} --shard-episodes {args.shard_episodes}",
                "shards": ray_run["shards"], "wall_s": round(ray_run["wall_s"], 2),
                "episodes_per_s": round(ray_run["episodes"] / ray_run["wall_s"], 4)},
        "ray_over_one_machine_time": round(ray_run["wall_s"] / one_wall, 3),
        "tables_equal": same,
    }
    text = json.dumps(report, indent=2)
    print(text)
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(text + "\n")
    return 0 if same else 1


def strip_wall_times(result):
    """A results.json without its rows' wall times, the one field two runs of the same episodes differ in."""
    for row in result["rows"]:
        row.pop("wall_time_s", None)
    return result


def main(argv=None):
    args = parse_args(argv)
    if not args.evaluate.is_file():
        sys.exit(f"error: evaluate not built ({args.evaluate}); build it or give --evaluate")
    if args.command == "bench":
        return bench(args)
    result = evaluate_on_ray(args)
    print(result["markdown"], end="")
    kept = result["shards"] - result["shards_run"]
    print(f"[cluster] {result['episodes']} episodes in {result['wall_s']:.0f} s ({result['shards']} shards: "
          f"{result['shards_run']} run, {kept} kept from an earlier run)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    # Through the module's importable name, so Ray workers import run_shard and ShardLost rather than
    # receiving copies of __main__'s.
    from guidewire_nav.cluster import main as cluster_main

    sys.exit(cluster_main())
