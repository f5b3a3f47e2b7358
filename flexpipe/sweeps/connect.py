"""Connect to the Dask scheduler of ``--scheduler``, or start a quiet local cluster.

Every way an address can be wrong ends in one :class:`~flexpipe.errors.InputError`
(key ``scheduler``) within seconds, naming the address, what was found there and the
likely fix:

* a malformed address (an unknown scheme such as ``nonsense://x``), before any work;
* nothing listening (connection refused, unknown host): a plain socket connect, bounded
  by :data:`PROBE_TIMEOUT_S`, before the Dask client is made;
* something that is not a Dask scheduler (the dashboard's HTTP port 8787, any other
  service): Dask's handshake read has no timeout of its own and may hang or fail on the
  foreign bytes, so the client is made in a helper thread with an overall deadline of
  :data:`CONNECT_TIMEOUT_S`.

The local cluster's workers ignore SIGINT (the client process handles Ctrl-C and closes
them), and the ``distributed`` loggers are raised to CRITICAL while the client and
cluster close, so an interrupted sweep ends on flexpipe's one "interrupted" line, not on
worker tracebacks.
"""

from __future__ import annotations

import contextlib
import logging
import os
import signal
import socket
import threading

from flexpipe.errors import InputError

#: Seconds allowed for the TCP connection to the scheduler's host and port.
PROBE_TIMEOUT_S = 3.0
#: Seconds allowed for the whole Dask connection (TCP connection and handshake).
CONNECT_TIMEOUT_S = 10.0

SCHEMES = ("tcp", "tls", "inproc", "ws", "wss")
_HINT = ("start one with `dask scheduler` (it listens on port 8786), or leave out "
         "--scheduler for a local cluster")


def _fail(address: str, what: str, hint: str = _HINT) -> InputError:
    return InputError(f"--scheduler {address}: {what}; {hint}", key="scheduler")


def check_scheduler_address(address: str) -> tuple[str, str | None, int | None]:
    """Check the form of a scheduler address, before any work.

    Parameters
    ----------
    address : str
        ``tcp://host:port``, ``tls://``, ``ws://``, ``wss://``, ``inproc://...`` or
        ``host:port`` (TCP).

    Returns
    -------
    scheme : str
        The scheme (``tcp`` for ``host:port``).
    host : str or None
        Host name or IP address (None for ``inproc``).
    port : int or None
        Port number (None for ``inproc``, or when the address gives none).

    Raises
    ------
    InputError
        Not a string, an unknown scheme, or a port that is not a number in 1-65535.
    """
    if not isinstance(address, str) or not address.strip():
        raise _fail(repr(address), "expected an address such as tcp://host:8786",
                    "give the address the scheduler prints at start")
    address = address.strip()
    scheme, sep, rest = address.partition("://")
    if not sep:
        scheme, rest = "tcp", address
    scheme = scheme.lower()
    if scheme not in SCHEMES:
        raise _fail(address, f"unknown address scheme {scheme!r} (valid: "
                    f"{', '.join(s + '://' for s in SCHEMES)} or host:port)",
                    "e.g. --scheduler tcp://host:8786")
    if scheme == "inproc":
        return scheme, None, None
    hostport = rest.split("/", 1)[0]
    if hostport.startswith("["):  # [ipv6]:port
        host, _, tail = hostport[1:].partition("]")
        port_text = tail[1:] if tail.startswith(":") else ""
    elif hostport.count(":") == 1:
        host, port_text = hostport.split(":")
    else:
        host, port_text = hostport, ""
    if not host:
        raise _fail(address, "no host name", "e.g. --scheduler tcp://host:8786")
    if port_text == "":
        return scheme, host, None
    if not port_text.isdigit() or not 1 <= int(port_text) <= 65535:
        raise _fail(address, f"port {port_text!r} is not a number in 1-65535",
                    "e.g. --scheduler tcp://host:8786")
    return scheme, host, int(port_text)


def _probe(address: str, host: str, port: int, timeout: float) -> None:
    """A plain TCP connect: fails fast when nothing listens there."""
    try:
        with socket.create_connection((host, port), timeout=timeout):
            pass
    except ConnectionRefusedError:
        raise _fail(address, "connection refused: no Dask scheduler (nothing at all) "
                    f"listens on port {port} of {host}") from None
    except TimeoutError:
        raise _fail(address, f"no answer from {host}:{port} within {timeout:g} s (host down, "
                    "or a firewall drops the connection)",
                    "check the host and port, or " + _HINT) from None
    except OSError as exc:
        raise _fail(address, f"cannot connect ({exc.strerror or exc})",
                    "check the host name and port, or " + _HINT) from None


def _not_dask_hint(port: int | None) -> str:
    if port == 8787:
        return ("8787 is the Dask dashboard's port: give the scheduler's port, "
                "usually 8786, or " + _HINT)
    return "is it the dashboard port 8787 instead of the scheduler port 8786? or " + _HINT


def connect(address: str, *, timeout: float | None = None):
    """A :class:`dask.distributed.Client` of the scheduler at ``address``, or a clear error.

    Parameters
    ----------
    address : str
        Scheduler address (see :func:`check_scheduler_address`).
    timeout : float, optional
        Overall deadline of the connection, s (default :data:`CONNECT_TIMEOUT_S`); the
        TCP probe uses at most :data:`PROBE_TIMEOUT_S` of it.

    Returns
    -------
    dask.distributed.Client

    Raises
    ------
    InputError
        Key ``scheduler``: a malformed address, nothing listening, or something that is
        not a Dask scheduler (no handshake within ``timeout``, or foreign bytes).
    """
    from dask.distributed import Client

    timeout = CONNECT_TIMEOUT_S if timeout is None else float(timeout)
    scheme, host, port = check_scheduler_address(address)
    if scheme in ("tcp", "ws") and port is not None:
        _probe(address, host, port, min(PROBE_TIMEOUT_S, timeout))
    box: dict = {}

    def attempt():
        try:
            box["client"] = Client(address, timeout=timeout, set_as_default=False)
        except BaseException as exc:  # noqa: BLE001 - reported in the caller's thread
            box["error"] = exc
        if box.get("abandoned") and "client" in box:  # too late: nobody will use it
            with contextlib.suppress(Exception):
                box["client"].close()

    thread = threading.Thread(target=attempt, name="flexpipe-connect", daemon=True)
    thread.start()
    thread.join(timeout + 1.0)
    if thread.is_alive():
        box["abandoned"] = True
        raise _fail(address, f"something listens there but it is not a Dask scheduler "
                    f"(no Dask handshake within {timeout:g} s)", _not_dask_hint(port))
    if "error" in box:
        exc = box["error"]
        if isinstance(exc, KeyboardInterrupt):
            raise exc
        text = " ".join(f"{type(exc).__name__}: {exc}".split())[:200]
        raise _fail(address, f"not a Dask scheduler, or it did not answer as one ({text})",
                    _not_dask_hint(port)) from None
    return box["client"]


@contextlib.contextmanager
def _sigint_ignored():
    """SIGINT ignored while worker processes start, so that they inherit it."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)


def local_cluster(n_workers: int | None):
    """A local cluster of single-threaded worker processes that ignore SIGINT."""
    from dask.distributed import Client, LocalCluster

    n = n_workers or os.cpu_count() or 1
    with _sigint_ignored():
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                               host="127.0.0.1", dashboard_address=":0",
                               silence_logs=logging.ERROR)
    return Client(cluster), cluster


def close_quietly(client, cluster) -> None:
    """Close ``client`` and ``cluster`` (either may be None) with the ``distributed``
    loggers silenced, also when an interrupt is being handled."""
    names = ["distributed", *(n for n in logging.root.manager.loggerDict
                              if n.startswith("distributed."))]
    saved = {n: logging.getLogger(n).level for n in names}
    for n in names:
        logging.getLogger(n).setLevel(logging.CRITICAL + 1)
    try:
        for obj in (client, cluster):
            if obj is not None:
                with contextlib.suppress(Exception):
                    obj.close()
    finally:
        for n, level in saved.items():
            logging.getLogger(n).setLevel(level)


__all__ = ["CONNECT_TIMEOUT_S", "PROBE_TIMEOUT_S", "check_scheduler_address",
           "close_quietly", "connect", "local_cluster"]
