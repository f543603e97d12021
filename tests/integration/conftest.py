"""A real HTTP server on 127.0.0.1 that replays recorded responses and faults.

``loopback`` starts ``http.server`` in a thread on an ephemeral port.  Tests
register routes (path -> recorded body, status, scripted fault) and point the
clients at ``loopback.url`` through the ``IRONBARK_*_URL`` variables.  Faults:
HTTP status codes, a response slower than the client timeout, a body cut
short of its Content-Length, failing the first N requests, and a closed port
(connection refused) from ``closed_port_url``.  Nothing leaves the machine.
"""
from __future__ import annotations

import socket
import threading
import time
from dataclasses import dataclass
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from urllib.parse import parse_qs, urlsplit

import pytest

DATA = Path(__file__).resolve().parents[1] / "data"


@dataclass
class Route:
    body: bytes = b""
    status: int = 200
    content_type: str = "application/octet-stream"
    delay: float = 0.0            # [s] before answering (slow server)
    truncate: bool = False        # announce the full length, send half, close
    fail_first: int = 0           # answer 500 to the first N requests
    calls: int = 0
    #: (query parameter, {value: body}): the body chosen by one query value (e.g. an NCSS ``time``),
    #: or ((parameters, ...), {(values, ...): body}) by several (``time`` and ``ensCoord``)
    by_query: tuple | None = None


class Loopback:
    """Routes keyed by URL path (query strings are recorded, not matched, unless a route
    picks its body by one query parameter: ``Route.by_query``)."""

    def __init__(self):
        self.routes: dict[str, Route] = {}
        self.requests: list[dict] = []
        self.lock = threading.Lock()
        server = self

        class Handler(BaseHTTPRequestHandler):
            protocol_version = "HTTP/1.1"

            def log_message(self, *args):
                pass

            def _serve(self, method):
                parts = urlsplit(self.path)
                length = int(self.headers.get("Content-Length") or 0)
                body = self.rfile.read(length) if length else b""
                with server.lock:
                    server.requests.append({"method": method, "path": parts.path,
                                            "query": parse_qs(parts.query), "body": body,
                                            "headers": dict(self.headers)})
                    route = server.routes.get(parts.path)
                    if route is not None:
                        route.calls += 1
                if route is None:
                    return self._send(404, b"Not Found\n", "text/plain")
                if route.delay:
                    time.sleep(route.delay)
                if route.calls <= route.fail_first:
                    return self._send(500, b"Internal Server Error\n", "text/plain")
                data, status = route.body, route.status
                if route.by_query is not None:
                    name, bodies = route.by_query
                    query = parse_qs(parts.query)
                    value = (tuple(query.get(n, [None])[0] for n in name) if isinstance(name, tuple)
                             else query.get(name, [None])[0])
                    if value not in bodies:
                        return self._send(400, f"no recorded response for {name}={value}\n".encode(),
                                          "text/plain")
                    data = bodies[value]
                rng = self.headers.get("Range")
                if rng and status == 200 and rng.startswith("bytes="):
                    start, _, end = rng[6:].partition("-")
                    stop = len(data) if not end else int(end) + 1
                    data, status = data[int(start):stop], 206
                if route.truncate:
                    self.send_response(status)
                    self.send_header("Content-Type", route.content_type)
                    self.send_header("Content-Length", str(len(data)))
                    self.end_headers()
                    self.wfile.write(data[: len(data) // 2])
                    self.wfile.flush()
                    self.close_connection = True
                    try:
                        self.connection.shutdown(socket.SHUT_RDWR)
                    except OSError:
                        pass
                    return None
                return self._send(status, data, route.content_type)

            def _send(self, status, data, ctype):
                try:
                    self.send_response(status)
                    self.send_header("Content-Type", ctype)
                    self.send_header("Content-Length", str(len(data)))
                    self.end_headers()
                    self.wfile.write(data)
                except (BrokenPipeError, ConnectionResetError):
                    self.close_connection = True   # the client gave up (timeout test)

            def do_GET(self):
                self._serve("GET")

            def do_POST(self):
                self._serve("POST")

        self.httpd = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.httpd.daemon_threads = True
        self.url = f"http://127.0.0.1:{self.httpd.server_address[1]}"
        self.thread = threading.Thread(target=self.httpd.serve_forever,
                                       kwargs={"poll_interval": 0.05}, daemon=True)
        self.thread.start()

    def route(self, path: str, body: bytes | str | Path = b"", **kw) -> Route:
        """Serve ``body`` (bytes, text, or a file under tests/data) at ``path``."""
        if isinstance(body, Path):
            body = body.read_bytes()
        elif isinstance(body, str):
            body = body.encode()
        r = Route(body=body, **kw)
        self.routes[path] = r
        return r

    def paths(self) -> list[str]:
        return [r["path"] for r in self.requests]

    def close(self):
        self.httpd.shutdown()
        self.httpd.server_close()


@pytest.fixture
def loopback():
    server = Loopback()
    yield server
    server.close()


@pytest.fixture
def closed_port_url():
    """URL of a 127.0.0.1 port that nothing listens on (connection refused)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    return f"http://127.0.0.1:{port}"


def isolate_network(monkeypatch, tmp: Path, url: str = "http://127.0.0.1:9") -> Path:
    """Isolated cache and config, fast retries, every service endpoint at ``url`` (by
    default the discard port: never the internet); returns the cache directory."""
    cache = tmp / "cache"
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(cache))
    monkeypatch.setenv("IRONBARK_CONFIG", str(tmp / "no-config.toml"))
    monkeypatch.setenv("IRONBARK_HTTP_RETRIES", "1")
    monkeypatch.setenv("IRONBARK_HTTP_BACKOFF", "0")
    monkeypatch.setenv("IRONBARK_HTTP_TIMEOUT", "2")
    monkeypatch.delenv("IRONBARK_OFFLINE", raising=False)
    for var in ("IRONBARK_THRUSTCURVE_URL", "IRONBARK_THREDDS_URL", "IRONBARK_NOMADS_URL",
                "IRONBARK_GFS_ARCHIVE_URL", "IRONBARK_RAP_ARCHIVE_URL", "IRONBARK_UWYO_URL"):
        monkeypatch.setenv(var, url)
    return cache


@pytest.fixture
def net_env(tmp_path, monkeypatch):
    """Isolated cache and config, fast retries; returns the cache directory."""
    return isolate_network(monkeypatch, tmp_path)


def cache_files(cache: Path) -> list[Path]:
    """All files in the cache, including any leftover temporary files."""
    return sorted(p for p in cache.rglob("*") if p.is_file()) if cache.exists() else []


THRUSTCURVE_API = "/api/v1"


@pytest.fixture
def tc_server(loopback, net_env, monkeypatch):
    """The loopback server standing in for ThrustCurve.org (API under ``/api/v1``)."""
    monkeypatch.setenv("IRONBARK_THRUSTCURVE_URL", loopback.url + THRUSTCURVE_API)
    return loopback


def scaled_point_csv(path: Path, stamp: str, factor: float, wind_columns: tuple[int, int]) -> bytes:
    """An NCSS point CSV (header + rows) with its first column (time) set to ``stamp`` and the two
    wind columns multiplied by ``factor``: one forecast hour built from one file."""
    lines = path.read_text().splitlines()
    out = [lines[0]]
    i, j = wind_columns
    for line in lines[1:]:
        cells = line.split(",")
        cells[0] = stamp
        cells[i], cells[j] = (f"{float(c) * factor:.6f}" for c in (cells[i], cells[j]))
        out.append(",".join(cells))
    return ("\n".join(out) + "\n").encode()
