"""guidewire-server from the outside: CLI start-up contract and the JSON-lines protocol over raw sockets."""

import json
import signal
import socket
import subprocess

import pytest

from guidewire_nav.env import find_server_binary, start_server


@pytest.fixture(scope="module")
def server():
    path = find_server_binary()
    if not path.is_file():
        pytest.skip(f"guidewire-server not built ({path}); set GW_SERVER_BIN or GW_BUILD_DIR")
    proc, port = start_server("t1_straight_y")
    yield proc, port
    proc.send_signal(signal.SIGINT)
    assert proc.wait(timeout=10) == 0


class Conn:
    def __init__(self, port):
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=30)
        self.file = self.sock.makefile("rb")

    def ask(self, raw: bytes):
        self.sock.sendall(raw + b"\n")
        line = self.file.readline()
        return json.loads(line) if line else None

    def close(self):
        self.file.close()
        self.sock.close()


def test_spec_reset_step_close(server):
    _, port = server
    c = Conn(port)
    spec = c.ask(b'{"cmd":"spec"}')
    assert spec["ok"] and spec["protocol"] == "guidewire-nav/protocol/1"
    assert spec["observation_space"]["shape"] == [12] and spec["action_space"]["shape"] == [1]  # obs/3
    r = c.ask(b'{"cmd":"reset","seed":3,"options":{"target":1}}')
    assert r["ok"] and len(r["obs"]) == 12 and r["info"]["target"] == 1
    s = c.ask(b'{"cmd":"step","action":[0.5]}')
    assert s["ok"] and set(s) >= {"obs", "reward", "terminated", "truncated", "info"}
    assert c.ask(b'{"cmd":"close"}') == {"ok": True}
    assert c.file.readline() == b""
    c.close()


@pytest.mark.parametrize(
    "raw, fragment",
    [
        (b"{not json", "malformed JSON"),
        (b'{"cmd":"dance"}', "unknown cmd"),
        (b'{"cmd":"step","action":[0.1,0.2]}', "expected 1"),
        (b'{"cmd":"step","action":[NaN]}', "malformed JSON"),
        (b'{"cmd":"step","action":[null]}', "not a number"),
        (b'{"cmd":"reset","seed":-1}', "seed"),
    ],
)
def test_bad_messages_get_an_error_reply(server, raw, fragment):
    _, port = server
    c = Conn(port)
    c.ask(b'{"cmd":"reset","seed":1}')
    reply = c.ask(raw)
    assert reply["ok"] is False and fragment in reply["error"]
    assert c.ask(b'{"cmd":"step","action":[0.0]}')["ok"]  # the connection still works
    c.close()


def test_oversized_line_and_vanishing_client_leave_the_server_serving(server):
    proc, port = server
    big = Conn(port)
    reply = big.ask(b"x" * 200_000)
    assert reply["ok"] is False and "longer than" in reply["error"]
    assert big.file.readline() == b""  # disconnected
    big.close()
    gone = socket.create_connection(("127.0.0.1", port))
    gone.sendall(b'{"cmd":"res')
    gone.close()
    c = Conn(port)
    assert c.ask(b'{"cmd":"spec"}')["ok"]
    c.close()
    assert proc.poll() is None


def test_cli_refuses_unknown_anatomy():
    path = find_server_binary()
    if not path.is_file():
        pytest.skip("guidewire-server not built")
    out = subprocess.run([str(path), "--port", "0", "--anatomies", "no_such_anatomy"], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 1
    assert "no_such_anatomy" in out.stderr


def test_a_users_inward_surface_is_repaired_and_served(tmp_path):
    """The server takes a user's mesh (with its .truth.json beside it) through the same mesh intake as
    navigate: t1 with every triangle reversed is repaired, not refused, and episodes run on it."""
    import shutil
    import struct

    import numpy as np

    path = find_server_binary()
    if not path.is_file():
        pytest.skip(f"guidewire-server not built ({path}); set GW_SERVER_BIN or GW_BUILD_DIR")
    from pathlib import Path
    t1 = Path(__file__).resolve().parents[2] / "anatomies/train/t1_straight_y/t1_straight_y"
    raw = (t1.with_suffix(".stl")).read_bytes()
    n = struct.unpack("<I", raw[80:84])[0]
    facets = np.frombuffer(raw[84:84 + 50 * n], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])).copy()
    facets["v"] = facets["v"][:, ::-1, :]  # reverse every triangle: normals into the lumen
    mesh = tmp_path / "inward.stl"
    mesh.write_bytes(raw[:84] + facets.tobytes())
    shutil.copy(t1.with_suffix(".truth.json"), tmp_path / "inward.truth.json")

    proc = subprocess.Popen([str(path), "--port", "0", "--host", "127.0.0.1", "--anatomies", str(mesh)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    try:
        port = int(json.loads(proc.stdout.readline())["port"])
        c = Conn(port)
        r = c.ask(b'{"cmd":"reset","seed":1,"options":{"target":2}}')
        assert r["ok"], r
        s = c.ask(b'{"cmd":"step","action":[0.0]}')
        assert s["ok"] and not s["info"].get("diverged", False), s
        c.close()
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=10)
    err = proc.stderr.read().decode()
    assert "repaired:" in err and "reversed" in err, err
