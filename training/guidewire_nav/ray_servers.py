"""Simulation servers as Ray actors (issue 40; `gw-train --ray [--address]`, docs/cluster.md).

Each server is a Ray actor that runs `guidewire-server` with train.py's task settings on whatever node Ray
places it (spread over the cluster) and tells where it listens. Ray restarts an actor whose process or
node dies (max_restarts=-1), and the actor starts its server again when the server alone died. The
environment the learner steps (ServerEnv, a GuidewireEnv client) notices a broken connection, asks its
actor for the server's new address and goes on: the episode the death cut short ends as truncated
(info["server_restarted"]), the next reset draws from the same seeded stream. The SAC updates stay on
the learner; only the simulation is spread.

    refs = start_servers(["0", "1", "eval"], "train", server_args(s), address="")   # in train.main
    env = ServerEnv(refs["0"])                                                       # in a worker thunk
"""

from __future__ import annotations

import ctypes
import json
import os
import select
import signal
import subprocess
import time
from dataclasses import dataclass

from guidewire_nav.env import GuidewireEnv, RestartingEnv, find_server_binary


@dataclass(frozen=True)
class ServerRef:
    """What an environment (in any process) needs to reach a server actor: its first address, and the
    actor's name with the Ray cluster to ask for the next one after a restart."""

    name: str          # the actor's name (Ray namespace `namespace`)
    namespace: str
    ray_address: str   # the GCS address of the cluster the actor lives on
    host: str
    port: int


def _die_with_parent() -> None:  # pragma: no cover - runs in the child before exec
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


class SimulationServer:
    """A guidewire-server on this node (the Ray actor; start_servers makes it remote)."""

    def __init__(self, name: str, binary: str, anatomies: str, server_args: list[str], listen: str):
        import ray

        self.name = name
        self.command = [binary, "--port", "0", "--host", listen, "--anatomies", anatomies, *server_args]
        self.host = "127.0.0.1" if listen == "127.0.0.1" else ray.util.get_node_ip_address()
        self.starts = 0
        self._start()

    def _start(self) -> None:
        env = dict(os.environ, GW_SERVER_NAME=self.name)  # names the process for tests and `ps e`
        self.proc = subprocess.Popen(self.command, stdout=subprocess.PIPE, stdin=subprocess.DEVNULL, env=env,
                                     preexec_fn=_die_with_parent)
        ready, _, _ = select.select([self.proc.stdout], [], [], 300)
        line = self.proc.stdout.readline() if ready else b""
        if not line:
            self.proc.kill()
            raise RuntimeError(f"guidewire-server did not start: {' '.join(self.command)}")
        self.port = int(json.loads(line)["port"])
        self.proc.stdout.close()
        self.starts += 1

    def address(self) -> tuple[str, int, int]:
        """(host, port, starts so far), the server started again first if it died."""
        if self.proc.poll() is not None:
            self._start()
        return self.host, self.port, self.starts


def start_servers(names: list[str], anatomies: str, server_args: list[str], address: str = "",
                  cpus: dict[str, float] | None = None):
    """One server actor per name (Ray started here, or joined at `address`); returns ({name: ServerRef},
    the actor handles: keep them until the run ends, an actor goes with its last handle)."""
    import ray

    namespace = f"gw-train-{os.getpid()}"
    if not ray.is_initialized():
        if address:
            ray.init(address=address, namespace=namespace, log_to_driver=False)
        else:
            ray.init(namespace=namespace, include_dashboard=False, log_to_driver=False,
                     object_store_memory=200 * 1024 * 1024)
    actor = ray.remote(max_restarts=-1, max_task_retries=-1)(SimulationServer)
    listen = "0.0.0.0" if address else "127.0.0.1"  # a local Ray's servers stay on this machine's loopback
    handles = {}
    for name in names:
        handles[name] = actor.options(name=name, num_cpus=(cpus or {}).get(name, 1),
                                      scheduling_strategy="SPREAD").remote(
            name, str(find_server_binary().resolve()), anatomies, server_args, listen)
    gcs = ray.get_runtime_context().gcs_address
    refs = {}
    for name, handle in handles.items():
        host, port, _ = ray.get(handle.address.remote())
        refs[name] = ServerRef(name, namespace, gcs, host, port)
    return refs, handles


class ServerEnv(RestartingEnv):
    """GuidewireEnv on a server actor's server that survives the server's death (see the module doc):
    after the first address, each new connection asks the actor (restarted by Ray if it died, which
    starts its server again) where its server listens now."""

    def __init__(self, ref: ServerRef, timeout: float = 120.0):
        self.ref, self.timeout, self._connected = ref, timeout, False
        super().__init__(self._connect, name=f"server {ref.name}")

    def _connect(self) -> GuidewireEnv:
        if not self._connected:
            self._connected = True
            return GuidewireEnv(host=self.ref.host, port=self.ref.port, timeout=self.timeout)
        import ray

        if not ray.is_initialized():  # a SubprocVecEnv worker: join the learner's cluster to ask
            ray.init(address=self.ref.ray_address, namespace=self.ref.namespace, log_to_driver=False)
        deadline = time.monotonic() + 600
        while True:
            try:
                host, port, _ = ray.get(ray.get_actor(self.ref.name).address.remote(), timeout=300)
                return GuidewireEnv(host=host, port=port, timeout=self.timeout)
            except (OSError, ConnectionError, ray.exceptions.RayError):
                if time.monotonic() > deadline:
                    raise
                time.sleep(2)
