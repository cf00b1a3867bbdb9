"""gw-train --ray (issue 40): the simulation servers are Ray actors on a local Ray; one of them killed in
the middle of the run (SIGKILL, as a lost node would) is started again and the run finishes all its steps."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from guidewire_nav.env import find_server_binary

REPO = Path(__file__).resolve().parents[2]


def server_processes() -> dict[str, int]:
    """{GW_SERVER_NAME: pid} of the guidewire-servers this machine runs for Ray actors."""
    out = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            if not (entry / "cmdline").read_bytes().split(b"\0")[0].endswith(b"guidewire-server"):
                continue
            env = dict(v.split(b"=", 1) for v in (entry / "environ").read_bytes().split(b"\0") if b"=" in v)
        except OSError:
            continue
        if b"GW_SERVER_NAME" in env and env.get(b"GW_TEST_RUN") == str(os.getpid()).encode():
            out[env[b"GW_SERVER_NAME"].decode()] = int(entry.name)
    return out


def test_training_goes_on_when_a_server_dies(tmp_path):
    pytest.importorskip("ray")  # the [cluster] extra; scripts/install.sh installs it
    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")
    argv = [sys.executable, "-m", "guidewire_nav.train", "--ray", "--out", str(tmp_path), "--anatomies",
            "t1_straight_y", "--total-steps", "240", "--learning-starts", "100", "--envs", "2", "--eval-every", "0",
            "--eval-episodes", "1", "--checkpoint-every", "100", "--no-progress", "--device", "cpu"]
    env = dict(os.environ, GW_TEST_RUN=str(os.getpid()))  # inherited by the Ray actors and their servers
    run = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=REPO, env=env)
    killed = None
    try:
        deadline = time.monotonic() + 600
        while killed is None and run.poll() is None and time.monotonic() < deadline:
            # At step 100 (the first checkpoint; an episode lasts ~160), kill a training server mid-episode.
            servers = server_processes()
            if (tmp_path / "checkpoints" / "sac_100_steps.zip").is_file() and "server-1" in servers:
                os.kill(servers["server-1"], signal.SIGKILL)
                killed = servers["server-1"]
            time.sleep(0.5)
        stdout, stderr = run.communicate(timeout=900)
    finally:
        if run.poll() is None:
            run.kill()
    assert killed is not None, "the run ended before a server could be killed"
    assert run.returncode == 0, stderr[-3000:]
    assert "server server-1: connection lost" in stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["steps"] >= 240
    assert (tmp_path / "actor.json").is_file()
