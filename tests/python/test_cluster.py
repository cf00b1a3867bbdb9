"""gw-cluster evaluate (issue 40) on a local Ray with 2 CPUs: the table it joins from episode shards run as
Ray tasks is the one-machine `evaluate` table with the same flags (results.json but for the rows' wall
times, and results.md to the byte), also when a Ray worker is killed in the middle of a shard.

A small table: two sensitivity rows of 3 episodes, push-only, ground-truth centerlines, one reachability
seed; shards of 2 episodes, so each row is joined from two shards (episodes 0-1, 2). Push-only misses
two var1 episodes: the join's reachability verdicts (a target no shard reached) and ceiling lists (in
episode order across shards) are compared too."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import guidewire_nav

REPO = Path(__file__).resolve().parents[2]
FLAGS = ["--controllers", "push-only", "--centerlines", "truth", "--episode-scale", "0.06",
         "--reachability-seeds", "1", "--seed", "7", "--rows", "var1,var3"]


@pytest.fixture(scope="module")
def evaluate():
    pytest.importorskip("ray")  # the [cluster] extra; scripts/install.sh installs it
    path = guidewire_nav.app_path("evaluate")
    if not path.is_file():
        pytest.skip(f"evaluate not built ({path}); set GW_BUILD_DIR")
    return path


def table(out: Path) -> dict:
    """results.json without the rows' wall times (a joined row's is its shards' sum)."""
    result = json.loads((out / "results.json").read_text())
    for row in result["rows"]:
        row.pop("wall_time_s")
    return result


def cluster_command(evaluate, out: Path) -> list[str]:
    return [sys.executable, "-m", "guidewire_nav.cluster", "evaluate", "--evaluate", str(evaluate), "--cpus", "2",
            "--shard-episodes", "2", "--out", str(out), *FLAGS]


@pytest.fixture(scope="module")
def one_machine(evaluate, tmp_path_factory):
    out = tmp_path_factory.mktemp("one")
    done = subprocess.run([str(evaluate), *FLAGS, "--threads", "2", "--out", str(out)], capture_output=True,
                          text=True, cwd=REPO, timeout=600)
    assert done.returncode == 0, done.stderr
    return out


def test_cluster_table_equals_the_one_machine_table(evaluate, one_machine, tmp_path):
    done = subprocess.run(cluster_command(evaluate, tmp_path), capture_output=True, text=True, cwd=REPO,
                          timeout=600)
    assert done.returncode == 0, done.stderr
    assert "4 shard(s)" in done.stderr  # two rows of 3 episodes in shards of 2: really split
    one, joined = table(one_machine), table(tmp_path)
    assert [r["name"] for r in joined["rows"]] == ["sensitivity: var1", "sensitivity: var3"]
    assert [r["episodes"] for r in joined["rows"]] == [3, 3]
    assert joined["rows"][0]["ceiling"]["reached_only_by_a_schedule"]  # the probes' join is exercised
    assert joined == one  # same episodes, outcomes, steps, forces, probes, settings
    assert (tmp_path / "results.md").read_text() == (one_machine / "results.md").read_text()
    assert "(4 shards: 4 run, 0 kept from an earlier run)" in done.stderr
    # Resumed with every shard in: nothing runs again, the summary says so, the table is the same.
    again = subprocess.run(cluster_command(evaluate, tmp_path) + ["--resume"], capture_output=True, text=True,
                           cwd=REPO, timeout=600)
    assert again.returncode == 0, again.stderr
    assert "(4 shards: 0 run, 4 kept from an earlier run)" in again.stderr
    assert table(tmp_path) == one


def descendants(pid: int) -> list[int]:
    """Every process under `pid` (Linux /proc)."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(entry.name))
    out, todo = [], [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            out.append(child)
            todo.append(child)
    return out


def cmdline(pid: int) -> list[str]:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().decode(errors="replace").split("\0")
    except OSError:
        return []


def parent(pid: int) -> int:
    return int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])


def test_a_worker_killed_mid_run_still_gives_the_full_equal_table(evaluate, one_machine, tmp_path):
    run = subprocess.Popen(cluster_command(evaluate, tmp_path), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           text=True, cwd=REPO)
    killed = None
    try:
        deadline = time.monotonic() + 300
        while killed is None and run.poll() is None and time.monotonic() < deadline:
            # An evaluate shard running under a Ray worker: kill the worker (SIGKILL, as a lost node would).
            for pid in descendants(run.pid):
                if "--episodes" in cmdline(pid) and Path(cmdline(pid)[0]).name == "evaluate":
                    worker = parent(pid)
                    os.kill(worker, signal.SIGKILL)
                    killed = (worker, pid)
                    break
            time.sleep(0.2)
        stdout, stderr = run.communicate(timeout=600)
    finally:
        if run.poll() is None:
            run.kill()
    assert killed is not None, "no shard was seen running to kill"
    assert run.returncode == 0, stderr
    assert table(tmp_path) == table(one_machine)  # every episode once: nothing lost, nothing twice
    assert (tmp_path / "results.md").read_text() == (one_machine / "results.md").read_text()
