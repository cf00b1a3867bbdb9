"""gw-bench-train (issue 62 item 5): one JSON object with every part of a training step, each a positive finite
time, and the loop's throughput per config; its schedule arithmetic is SB3's; a malformed config is refused by
name. The times themselves are not asserted (never wall-clock in a test)."""
import json
import math
import subprocess
import sys

import pytest

from conftest import REPO, app_or_skip
from guidewire_nav.bench_train import gradient_steps_per_env_step, parse_config


def test_schedule_arithmetic():
    assert gradient_steps_per_env_step(parse_config("shipped"), 2) == 1.0  # -1: one per env step
    assert gradient_steps_per_env_step(parse_config("fed"), 2) == 0.25  # 2 per 4 vector steps of 2 envs
    c = parse_config("x=8:1:128:64x64:1")
    assert (c["train_freq"], c["gradient_steps"], c["batch_size"], c["net_arch"], c["torch_threads"]) == \
        (8, 1, 128, [64, 64], 1)
    assert gradient_steps_per_env_step(c, 1) == 0.125
    assert not c["overlap"] and c["envs"] is None
    o = parse_config("overlapped")  # fed's ratio with 4 servers and gw-train --overlap
    assert o["overlap"] and o["envs"] == 4 and gradient_steps_per_env_step(o, o["envs"]) == 0.25
    assert parse_config("y=2:1:64:64:0:e3")["envs"] == 3


@pytest.mark.parametrize("bad", ["nope", "x=1:2:3", "x=a:b:c:d:e", "x=1:1:8:8:0:fast", "x=1:1:8:8:0:e0",
                                 "x=1:1:8:8:0:e2:e3"])
def test_a_malformed_config_is_named(bad):
    with pytest.raises(SystemExit) as e:
        parse_config(bad)
    assert bad in str(e.value)


def test_one_json_object_with_every_part(tmp_path):
    app_or_skip("guidewire-server")
    out = tmp_path / "bench.json"
    r = subprocess.run([sys.executable, "-m", "guidewire_nav.bench_train", "--envs", "1", "--steps", "20",
                        "--configs", "tiny=2:1:32:32x32:1", "--out", str(out)],
                       capture_output=True, text=True, cwd=REPO, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    report = json.loads(r.stdout)
    assert json.loads(out.read_text()) == report
    times = [report["simulation"]["step_ms"], report["simulation"]["socket_round_trip_ms"],
             report["vec_env"]["vector_step_ms"]]
    (config,) = report["configs"]
    times += [config[k] for k in ("gradient_step_ms", "add_ms", "sample_ms", "measured_env_steps_per_s",
                                  "predicted_env_steps_per_s")]
    assert all(math.isfinite(t) and t > 0 for t in times), times
    assert config["name"] == "tiny" and config["gradient_steps_per_env_step"] == 0.5
    assert config["torch_threads_used"] == 1
