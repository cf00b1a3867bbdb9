"""Gymnasium environment backed by the C++ guidewire simulator (``guidewire-server``).

By default the environment starts its own local server process (``--port 0``, it prints the port it
got) and talks to it over a TCP socket with the newline-delimited JSON protocol of docs/architecture.md ("The socket protocol"); pass
``host``/``port`` to use a server that is already running, e.g. on another machine.

    env = GuidewireEnv()                                   # own server, the 4 training anatomies
    env = GuidewireEnv(host="10.0.0.5", port=5555)         # remote server
    env = GuidewireEnv(options={"anatomy": "t1_straight_y", "target": 2})

The task is the server's (``server_args=["--task", FILE_OR_JSON]`` and the task flags, docs/task_settings.md; the
spec's ``task`` holds all of it). Observation (the spec's ``obs_layout``, task/observation.hpp): by default
"guidewire-nav/obs/3", the shipped actor's, 12 float32 values: theta_t (3), theta_{t-n dt} (3), lambda_t,
lambda_{t-n dt}, a_t, omega (in the approach plane), s, omega_side (omega's sine). The paper's "guidewire-nav/obs/1"
(11 values, omega in the correct branch's normal plane): ``server_args=["--task", "training/tasks/paper.json"]``
(with the paper's reward sigmoid) or ``server_args=["--omega-plane", "correct_branch"]``; "guidewire-nav/obs/5"
(``server_args=["--push-pull"]``, 14 values) adds the last insertion and a wrong-branch flag. The exported actor
records which one it was trained on.  Action (the spec's ``action_layout``): one
float in [-1, 1], the proximal rotation rate as a fraction of the maximum ("guidewire-nav/act/1", paper Eq. 3's
reward with the task's sigmoid); with ``--push-pull`` two, rotation and insertion speed ("guidewire-nav/act/2",
task/reward.hpp).
Info after a step: the server's fields (anatomy, target, success, wrong_branch, stuck, step_limit, ...)
and ``is_success`` (= success; the name SB3 reads).

Registered with gymnasium on ``import guidewire_nav``: ``gym.make("GuidewireNav-v0", **kwargs)`` with
the keyword arguments of GuidewireEnv.
"""

from __future__ import annotations

import json
import math
import os
import select
import signal
import socket
import subprocess
import sys
from pathlib import Path
from typing import Any, Callable

import gymnasium as gym
import numpy as np

import guidewire_nav

PROTOCOL = "guidewire-nav/protocol/1"
# The observation layout is the server's (spec: "obs_layout" and observation_space.names; C++
# ObservationLayout, task/observation_layout.hpp): obs/1, 11 values, the paper's omega; obs/3: omega in the
# approach plane and its sine (12 values); obs/4 and obs/6: obs/3 with combined or k-way junctions; obs/5: obs/3 with
# the push/pull entries (14 values). The client reads what it needs (omega's index) from the names and keeps no copy
# of the layouts.


class ServerError(RuntimeError):
    """The server answered a request with ``"ok": false``."""


def find_server_binary() -> Path:
    """The ``guidewire-server`` executable: $GW_SERVER_BIN, else <$GW_BUILD_DIR or BUILD_DIR>/apps/."""
    explicit = os.environ.get("GW_SERVER_BIN")
    if explicit:
        return Path(explicit)
    return guidewire_nav.app_path("guidewire-server")


def _die_with_parent() -> None:  # pragma: no cover - runs in the child before exec
    # Linux: the server gets SIGTERM when the Python process that started it dies, even by SIGKILL.
    try:
        import ctypes

        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except Exception:
        pass


def start_server(
    anatomies: str = "train", binary: str | os.PathLike | None = None, extra_args: list[str] | None = None,
    timeout: float = 120.0,
) -> tuple[subprocess.Popen, int]:
    """Starts a local server on a free port; returns (process, port)."""
    binary = Path(binary) if binary else find_server_binary()
    if not binary.is_file():
        raise FileNotFoundError(
            f"{binary}: guidewire-server not found; build it (cmake --build build --target guidewire-server) "
            "or set GW_SERVER_BIN / GW_BUILD_DIR"
        )
    cmd = [str(binary), "--port", "0", "--host", "127.0.0.1", "--anatomies", anatomies, *(extra_args or [])]
    proc = subprocess.Popen(
        cmd, stdout=subprocess.PIPE, stdin=subprocess.DEVNULL,
        preexec_fn=_die_with_parent if sys.platform.startswith("linux") else None,
    )
    assert proc.stdout is not None
    ready, _, _ = select.select([proc.stdout], [], [], timeout)
    line = proc.stdout.readline() if ready else b""
    if not line:
        proc.kill()
        proc.wait()
        raise RuntimeError(f"guidewire-server did not start (exit code {proc.returncode}): {' '.join(cmd)}")
    port = int(json.loads(line)["port"])
    proc.stdout.close()  # nothing else is printed on stdout
    return proc, port


class GuidewireEnv(gym.Env):
    """Paper section 2.2 navigation task: constant push, the agent controls the rotation."""

    metadata = {"render_modes": []}

    def __init__(
        self,
        host: str | None = None,
        port: int | None = None,
        anatomies: str = "train",
        options: dict[str, Any] | None = None,
        server_binary: str | os.PathLike | None = None,
        server_args: list[str] | None = None,
        timeout: float = 120.0,
        heart_rate_bpm: float = 0.0,
        motion: str | os.PathLike | None = None,
    ):
        """``options`` are the default reset options ({"anatomy": name or index, "target": id});
        without them every reset draws an anatomy and a target from its seed.
        ``heart_rate_bpm`` > 0 (or a ``motion`` JSON) makes every anatomy's vessel beat, its wall and centerline
        following ``motion`` or the anatomy's own cardiac field (the server's ``--heart-rate``/``--motion``,
        docs/beating_heart.md); only for a server this environment starts itself."""
        super().__init__()
        heart_args: list[str] = []
        if heart_rate_bpm:
            heart_args += ["--heart-rate", repr(float(heart_rate_bpm))]
        if motion is not None:
            heart_args += ["--motion", str(motion)]
        if heart_args and port is not None:
            raise ValueError("heart_rate_bpm and motion configure a server this environment starts; "
                             "start the remote server with --heart-rate/--motion instead")
        server_args = [*(server_args or []), *heart_args] if heart_args else server_args
        self._proc: subprocess.Popen | None = None
        self._sock: socket.socket | None = None
        if port is None:
            if host not in (None, "127.0.0.1", "localhost"):
                raise ValueError("give a port to connect to a remote server")
            self._proc, port = start_server(anatomies, server_binary, server_args, timeout)
            host = "127.0.0.1"
        self.host, self.port = host or "127.0.0.1", int(port)
        try:
            self._sock = socket.create_connection((self.host, self.port), timeout=timeout)
            self._sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            self._reader = self._sock.makefile("rb")
            self.spec_reply = self._request({"cmd": "spec"})
        except BaseException:
            self.close()
            raise
        obs_space = self.spec_reply.get("observation_space", {})
        if (self.spec_reply.get("protocol") != PROTOCOL or not str(self.spec_reply.get("obs_layout", "")).startswith(
                "guidewire-nav/obs/") or "omega" not in obs_space.get("names", [])):
            self.close()
            raise RuntimeError(
                f"server speaks {self.spec_reply.get('protocol')} / {self.spec_reply.get('obs_layout')} (observations "
                f"{obs_space.get('names')}), this client {PROTOCOL} with a guidewire-nav/obs/N layout that has omega"
            )
        self.observation_space = gym.spaces.Box(
            low=np.asarray(obs_space["low"], dtype=np.float32),
            high=np.asarray(obs_space["high"], dtype=np.float32),
            dtype=np.float32,
        )
        act_space = self.spec_reply["action_space"]
        self.action_space = gym.spaces.Box(
            low=np.asarray(act_space["low"], dtype=np.float32),
            high=np.asarray(act_space["high"], dtype=np.float32),
            dtype=np.float32,
        )
        self.observation_names = list(obs_space["names"])
        self.omega_index = self.observation_names.index("omega")  # what the scripted rule and schedules read
        self.anatomy_names = [a["name"] for a in self.spec_reply["anatomies"]]
        self.default_options = dict(options or {})

    # --- protocol ---------------------------------------------------------------------------------
    def _request(self, message: dict[str, Any]) -> dict[str, Any]:
        if self._sock is None:
            raise RuntimeError("environment is closed")
        self._sock.sendall(json.dumps(message, allow_nan=False).encode() + b"\n")
        line = self._reader.readline()
        if not line:
            raise ConnectionError(f"guidewire-server at {self.host}:{self.port} closed the connection")
        reply = json.loads(line)
        if not reply.get("ok", False):
            raise ServerError(reply.get("error", "server error without a message"))
        return reply

    def _obs(self, values: list[float]) -> np.ndarray:
        return np.asarray(values, dtype=np.float32)

    # --- gymnasium API ------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        # The episode seed comes from gymnasium's generator: reset(seed=s) is reproducible and
        # seedless resets continue the seeded stream.
        episode_seed = int(self.np_random.integers(0, 2**63 - 1))
        opts = dict(self.default_options)
        opts.update(options or {})
        reply = self._request({"cmd": "reset", "seed": episode_seed, "options": opts})
        return self._obs(reply["obs"]), reply["info"]

    def step(self, action):
        a = np.asarray(action, dtype=np.float64).reshape(-1)
        n = int(self.action_space.shape[0])
        if a.size != n:
            raise ValueError(f"action must hold {n} value{'s' if n > 1 else ''}, got {a.size}")
        values = [float(v) for v in a]
        if not all(math.isfinite(v) for v in values):
            raise ValueError(f"action is not finite: {values}")
        reply = self._request({"cmd": "step", "action": values})
        info = reply["info"]
        # "is_success" is the key SB3 (rollout/success_rate, EvalCallback) and other libraries read;
        # "success" is the server's own name, kept for code that reads it.
        info["is_success"] = bool(info.get("success", False))
        return (
            self._obs(reply["obs"]),
            float(reply["reward"]),
            bool(reply["terminated"]),
            bool(reply["truncated"]),
            info,
        )

    def close(self):
        if self._sock is not None:
            try:
                self._sock.settimeout(2.0)
                self._sock.sendall(b'{"cmd":"close"}\n')
                self._reader.readline()
            except OSError:
                pass
            try:
                self._reader.close()
            except Exception:
                pass
            self._sock.close()
            self._sock = None
        if self._proc is not None:
            if self._proc.poll() is None:
                self._proc.terminate()
                try:
                    self._proc.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    self._proc.kill()
                    self._proc.wait()
            self._proc = None
        super().close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass


class RestartingEnv(gym.Env):
    """A GuidewireEnv that outlives its server (training survives a dying simulation server).

    ``connect()`` makes the client: at the start and again whenever the connection breaks (the server
    died): a new local server (``RestartingEnv(lambda: GuidewireEnv(...))``, what gw-train does) or the
    restarted server of a Ray actor (ray_servers.ServerEnv). The episode the death cut short ends as
    truncated with ``info["server_restarted"]``; a reset that finds the server gone is retried once on
    the new one; the episode seeds go on from the same generator, so the run stays seeded. A step the server
    answers with an error (a step cut off by its --step-cutoff wall-time limit, e.g. a wire jammed in a narrow
    vessel where the simulation crawls) ends the episode as truncated with ``info["server_error"]``; the same
    server starts the next one."""

    metadata = {"render_modes": []}

    def __init__(self, connect: Callable[[], GuidewireEnv], name: str = "guidewire-server"):
        super().__init__()
        self.connect, self.name, self.restarts, self.step_errors = connect, name, 0, 0
        self.env = connect()
        self.observation_space, self.action_space = self.env.observation_space, self.env.action_space
        self.spec_reply = self.env.spec_reply
        self.observation_names, self.omega_index = self.env.observation_names, self.env.omega_index
        self._last_obs = None

    def _reconnect(self) -> None:
        rng = self.env.np_random
        try:
            self.env.close()
        except Exception:  # noqa: BLE001 - the connection is already broken
            pass
        self.env = self.connect()
        self.env.np_random = rng
        self.spec_reply = self.env.spec_reply
        self.restarts += 1
        print(f"[env] {self.name}: connection lost, on {self.env.host}:{self.env.port} again "
              f"(restart {self.restarts})", file=sys.stderr)

    def reset(self, *, seed=None, options=None):
        try:
            obs, info = self.env.reset(seed=seed, options=options)
        except (ConnectionError, OSError):
            self._reconnect()
            obs, info = self.env.reset(seed=seed, options=options)
        self._last_obs = obs
        return obs, info

    def step(self, action):
        try:
            obs, reward, terminated, truncated, info = self.env.step(action)
        except (ConnectionError, OSError):
            self._reconnect()  # the episode is lost with its server: ended as truncated, reset next
            return self._last_obs, 0.0, False, True, {"success": False, "is_success": False,
                                                      "server_restarted": True}
        except ServerError as e:  # the server refused the step or cut it off (--step-cutoff): the episode is over
            self.step_errors += 1
            print(f"[env] {self.name}: episode ended by the server: {e} (step error {self.step_errors})",
                  file=sys.stderr)
            return self._last_obs, 0.0, False, True, {"success": False, "is_success": False, "server_error": str(e)}
        self._last_obs = obs
        return obs, reward, terminated, truncated, info

    def close(self):
        self.env.close()
        super().close()


def make_env(rank: int = 0, **kwargs):
    """Factory for SB3 vector envs: ``SubprocVecEnv([make_env(i) for i in range(N)])`` (one server each)."""

    def _init():
        return GuidewireEnv(**kwargs)

    return _init
