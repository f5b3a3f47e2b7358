"""Sweep errors a user can cause outside the spec: a wrong ``--scheduler`` (malformed, nothing
listening, not a Dask scheduler) fails within seconds with one line naming the option and
the fix; ``--out`` never overwrites a folder of other files; ``[[runs]]`` errors name
``runs[i]``; the local cluster's workers leave Ctrl-C to the client."""

from __future__ import annotations

import signal
import socket
import threading
import time
from pathlib import Path

import pytest
from _rigidcar import rigid_sedan

import flexpipe as fp
from flexpipe.errors import InputError
from flexpipe.sweeps import connect as conn

ROOT = Path(__file__).resolve().parents[1]
ROAD = ROOT / "roads" / "iso_c_200m.toml"


def _spec_file(folder, text: str = "[parameters]\nspeed_kmh = [50.0, 60.0]\n") -> Path:
    from tests.test_sweep import _spec_file as spec_file

    return spec_file(folder, text)


class _Server:
    """A local TCP server that is not a Dask scheduler: it accepts and then sends
    ``reply`` (garbage) or nothing at all (a server that never answers)."""

    def __init__(self, reply: bytes | None):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(8)
        self.port = self.sock.getsockname()[1]
        self.reply = reply
        self.conns = []
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self):
        while True:
            try:
                c, _ = self.sock.accept()
            except OSError:
                return
            self.conns.append(c)
            if self.reply is not None:
                try:
                    c.sendall(self.reply)
                except OSError:
                    pass

    def close(self):
        self.sock.close()
        for c in self.conns:
            c.close()


@pytest.fixture(params=[None, b"HTTP/1.0 400 Bad request\r\n\r\n" + b"\xff" * 64],
                ids=["silent", "garbage"])
def not_dask(request):
    server = _Server(request.param)
    yield server
    server.close()


def _free_port() -> int:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def test_a_server_that_is_not_dask_fails_within_the_deadline(not_dask):
    address = f"tcp://127.0.0.1:{not_dask.port}"
    t0 = time.perf_counter()
    with pytest.raises(InputError) as info:
        conn.connect(address, timeout=1.5)
    assert time.perf_counter() - t0 < 8
    msg = str(info.value)
    assert info.value.key == "scheduler" and "--scheduler" in msg and address in msg
    assert "not a Dask scheduler" in msg and "8786" in msg and "dask scheduler" in msg
    assert "\n" not in msg


def test_cli_sweep_at_a_silent_server_ends_with_exit_2(not_dask, tmp_path, capsys,
                                                        monkeypatch):
    """The old code hung here (Dask's handshake read has no timeout)."""
    from flexpipe.cli import main

    monkeypatch.setattr(conn, "CONNECT_TIMEOUT_S", 1.5)
    path = _spec_file(tmp_path)
    box = {}
    t = threading.Thread(target=lambda: box.setdefault("code", main(
        ["sweep", str(path), "--out", str(tmp_path / "out"), "--no-progress",
         "--scheduler", f"tcp://127.0.0.1:{not_dask.port}"])), daemon=True)
    t.start()
    t.join(30)
    assert not t.is_alive(), "the sweep hangs on a server that is not a Dask scheduler"
    assert box["code"] == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--scheduler" in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_nothing_listening_fails_at_once_naming_the_option():
    address = f"tcp://127.0.0.1:{_free_port()}"
    t0 = time.perf_counter()
    with pytest.raises(InputError) as info:
        conn.connect(address)
    assert time.perf_counter() - t0 < 5
    msg = str(info.value)
    assert "--scheduler" in msg and "refused" in msg and "dask scheduler" in msg


@pytest.mark.parametrize("address", ["nonsense://x", "tcp://host:port", "tcp://:8786",
                                     "host:99999"])
def test_cli_rejects_a_malformed_scheduler_address(tmp_path, capsys, address):
    from flexpipe.cli import main

    path = _spec_file(tmp_path)
    out = tmp_path / "out"
    assert main(["sweep", str(path), "--out", str(out), "--scheduler", address]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--scheduler" in err and address in err
    assert not out.exists()


@pytest.mark.parametrize("address", ["tcp://10.0.0.5:8786", "tls://head:8786",
                                     "head.example:8786", "inproc://10.1.2.3/1/2",
                                     "ws://[::1]:8786"])
def test_valid_scheduler_addresses_pass_the_form_check(address):
    conn.check_scheduler_address(address)


def test_list_design_errors_name_the_run_table(tmp_path):
    from flexpipe.sweeps import load_sweep

    car = rigid_sedan(tmp_path)
    spec = {"sweep": {"car": str(car), "body": "rigid", "t_end_s": 0.3, "design": "list"},
            "runs": [{"speed_kmh": 40.0}, {"speedkmh": 50.0}]}
    with pytest.raises(InputError) as info:
        load_sweep(spec)
    assert info.value.key == "runs[1].speedkmh"


@pytest.mark.parametrize("files", [{"metrics.csv": "my,own,data\n", "notes.txt": "keep\n"},
                                   {"summary.json": "{}", "flexible.csv": "t\n"}],
                         ids=["user-data", "run-folder"])
def test_sweep_refuses_a_folder_of_other_files(tmp_path, capsys, files):
    from flexpipe.cli import main

    path = _spec_file(tmp_path)
    out = tmp_path / "mydata"
    out.mkdir()
    for name, text in files.items():
        (out / name).write_text(text)
    assert main(["sweep", str(path), "--out", str(out), "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "'--out'" in err and "holds other files" in err
    assert {p.name: p.read_text() for p in out.iterdir()} == files
    with pytest.raises(InputError, match="holds other files"):
        fp.sweep(path, out=out, progress=False)


def test_a_previous_sweeps_folder_is_accepted(tmp_path):
    from flexpipe.sweeps.store import MARKER, check_sweep_folder

    for name in ("empty", "marked", "old"):
        (tmp_path / name).mkdir()
    (tmp_path / "marked" / MARKER).write_text("")
    (tmp_path / "marked" / "metrics.csv").write_text("")
    (tmp_path / "old" / "runs").mkdir()
    (tmp_path / "old" / "metrics.csv").write_text("")
    for name in ("empty", "marked", "old", "absent"):
        check_sweep_folder(tmp_path / name)


def test_local_workers_ignore_sigint_and_close_quietly():
    client, cluster = conn.local_cluster(1)
    try:
        handlers = client.run(lambda: signal.getsignal(signal.SIGINT))
        assert list(handlers.values()) == [signal.SIG_IGN]
        assert signal.getsignal(signal.SIGINT) is not signal.SIG_IGN  # the client's is back
    finally:
        conn.close_quietly(client, cluster)
