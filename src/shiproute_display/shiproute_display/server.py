"""The display's HTTP server: its own page files, a few JSON routes and the live SSE feed.

Nothing else is served: the static files are a fixed table read once from the package (no
path from a URL ever reaches the file system, so there is no directory listing and no path
traversal), paths with `..`, backslashes or encoded dots are refused with 400, any other
path is 404 and any method but GET/HEAD 405. Binds to 127.0.0.1 unless told otherwise.
"""

from __future__ import annotations

import ipaddress
import re
import socket
import threading
from collections.abc import Callable
from dataclasses import dataclass
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from typing import Any
from urllib.parse import parse_qs, urlsplit

from .errors import DisplayConfigError
from .feed import RESYNC, Feed, FeedFullError, dumps

STATIC = {  # URL path -> (package file, content type)
    "/": ("index.html", "text/html; charset=utf-8"),
    "/index.html": ("index.html", "text/html; charset=utf-8"),
    "/app.js": ("app.js", "text/javascript; charset=utf-8"),
    "/chart.js": ("chart.js", "text/javascript; charset=utf-8"),
    "/style.css": ("style.css", "text/css; charset=utf-8"),
    "/favicon.svg": ("favicon.svg", "image/svg+xml"),
    "/licenses.txt": ("licenses.txt", "text/plain; charset=utf-8"),
}
SSE_SNDBUF_BYTES = 256 * 1024
_BAD_PATH = re.compile(r"(\.\.|%2e|%2f|%5c|\\|//|\x00)", re.IGNORECASE)
SECURITY_HEADERS = {
    "Content-Security-Policy": "default-src 'self'; img-src 'self' data:; "
                               "style-src 'self'; script-src 'self'; connect-src 'self'",
    "X-Content-Type-Options": "nosniff",
    "X-Frame-Options": "DENY",
    "Referrer-Policy": "no-referrer",
}


@dataclass(frozen=True)
class Routes:
    """What the server asks the display for (each returns JSON-ready data or bytes)."""

    snapshot: Callable[[], dict[str, Any]]
    coast: Callable[[], bytes]
    forecast_slice: Callable[[str, int, str], bytes | None]  # cycle, time index, member
    geojson: Callable[[], dict[str, Any]]
    health: Callable[[], dict[str, Any]]


def check_bind(host: str, port: int) -> None:
    """DisplayConfigError unless `host` is an IP address and `port` 0..65535."""
    try:
        ipaddress.ip_address(host)
    except ValueError as exc:
        raise DisplayConfigError(f"bind_address {host!r} is not an IP address") from exc
    if not 0 <= port <= 65535:
        raise DisplayConfigError(f"port {port} is not in 0..65535")


def _load_static() -> dict[str, tuple[bytes, str]]:
    web = resources.files("shiproute_display") / "web"
    return {path: (web.joinpath(name).read_bytes(), ctype) for path, (name, ctype)
            in STATIC.items()}


class _Server(ThreadingHTTPServer):
    daemon_threads = True
    allow_reuse_address = True
    request_queue_size = 32

    def __init__(self, addr: tuple[str, int], display: DisplayServer) -> None:
        self.address_family = socket.AF_INET6 if ":" in addr[0] else socket.AF_INET
        self.display = display
        super().__init__(addr, _Handler)

    def handle_error(self, request: Any, client_address: Any) -> None:
        """A connection that fails (reset, timeout, garbage) is counted, not printed."""
        self.display.count("connection errors")


class _Handler(BaseHTTPRequestHandler):
    server: _Server
    server_version = "shiproute-display"
    sys_version = ""
    timeout = 15.0  # a request must arrive within this (no half-open connections held)
    protocol_version = "HTTP/1.1"

    def log_message(self, format: str, *args: Any) -> None:
        return  # requests are counted, not logged line by line

    def _send(self, status: int, body: bytes, ctype: str, cache: bool = False) -> None:
        self.send_response(status)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "max-age=60" if cache else "no-store")
        for k, v in SECURITY_HEADERS.items():
            self.send_header(k, v)
        self.end_headers()
        if self.command != "HEAD":
            self.wfile.write(body)

    def _error(self, status: HTTPStatus, text: str) -> None:
        self.server.display.count("refused")
        self._send(status, f"{status.value} {status.phrase}: {text}\n".encode(),
                   "text/plain; charset=utf-8")

    def do_HEAD(self) -> None:
        self.do_GET()

    def do_GET(self) -> None:
        raw = self.path
        if _BAD_PATH.search(raw.split("?", 1)[0]):
            self._error(HTTPStatus.BAD_REQUEST, "path not allowed")
            return
        url = urlsplit(raw)
        path, query = url.path, parse_qs(url.query)
        d = self.server.display
        if path in d.static:
            body, ctype = d.static[path]
            self._send(HTTPStatus.OK, body, ctype, cache=False)
        elif path == "/events":
            self._events()
        elif path == "/api/snapshot":
            self._json(d.routes.snapshot())
        elif path == "/api/coast":
            self._send(HTTPStatus.OK, d.routes.coast(), "application/json")
        elif path == "/api/geojson":
            self._send(HTTPStatus.OK, dumps(d.routes.geojson()), "application/geo+json")
        elif path == "/api/health":
            self._json(d.routes.health())
        elif path == "/api/forecast":
            self._forecast(query)
        else:
            self._error(HTTPStatus.NOT_FOUND, "no such page")

    def _not_allowed(self) -> None:
        self._error(HTTPStatus.METHOD_NOT_ALLOWED, "only GET and HEAD")

    do_POST = do_PUT = do_DELETE = do_PATCH = do_OPTIONS = _not_allowed  # noqa: N815

    def _json(self, data: Any) -> None:
        self._send(HTTPStatus.OK, dumps(data), "application/json")

    def _forecast(self, query: dict[str, list[str]]) -> None:
        try:
            cycle = query["cycle"][0]
            index = int(query["index"][0])
            member = query.get("member", ["0"])[0]
            if member != "p90":
                int(member)
        except (KeyError, IndexError, ValueError):
            self._error(HTTPStatus.BAD_REQUEST, "need ?cycle=ID&index=N[&member=M|p90]")
            return
        body = self.server.display.routes.forecast_slice(cycle, index, member)
        if body is None:
            self._error(HTTPStatus.NOT_FOUND, f"no slice {index} of member {member} of cycle "
                                              f"{cycle!r}")
        else:
            self._send(HTTPStatus.OK, body, "application/json")

    def _events(self) -> None:
        d = self.server.display
        try:
            client = d.feed.subscribe()
        except FeedFullError as exc:
            self._error(HTTPStatus.SERVICE_UNAVAILABLE, str(exc))
            return
        try:
            self.send_response(HTTPStatus.OK)
            self.send_header("Content-Type", "text/event-stream")
            self.send_header("Cache-Control", "no-store")
            self.send_header("Connection", "close")
            for k, v in SECURITY_HEADERS.items():
                self.send_header(k, v)
            self.end_headers()
            self.close_connection = True
            self.connection.settimeout(d.client_timeout_s)  # a stalled reader is dropped
            # a small kernel send buffer: a page that stops reading shows up in its own bounded
            # queue within a few events instead of after megabytes parked in the kernel
            self.connection.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, SSE_SNDBUF_BYTES)
            self.wfile.write(b"retry: 2000\n\n")
            self.wfile.write(d.feed.frame("snapshot", d.routes.snapshot()))
            while not d.stopping.is_set() and not client.closed:
                frame = client.next(d.heartbeat_s)
                if frame is RESYNC:
                    frame = d.feed.frame("snapshot", d.routes.snapshot())
                elif frame is None:
                    frame = b": keep-alive\n\n"
                self.wfile.write(frame)
                client.sent += 1
        except OSError:
            pass  # the page went away or stopped reading: drop it
        finally:
            d.feed.unsubscribe(client)


class DisplayServer:
    """The HTTP server on its own threads (one per connection)."""

    def __init__(self, routes: Routes, feed: Feed, host: str = "127.0.0.1", port: int = 8765,
                 client_timeout_s: float = 10.0, heartbeat_s: float = 5.0) -> None:
        check_bind(host, port)
        self.routes = routes
        self.feed = feed
        self.client_timeout_s = client_timeout_s
        self.heartbeat_s = heartbeat_s
        self.static = _load_static()
        self.stopping = threading.Event()
        self.counts: dict[str, int] = {}
        self._httpd = _Server((host, port), self)
        self._thread: threading.Thread | None = None

    @property
    def address(self) -> tuple[str, int]:
        """(host, port) actually bound (port 0 asks the system for a free one)."""
        host, port = self._httpd.server_address[:2]
        return str(host), int(port)

    @property
    def url(self) -> str:
        """The page's URL."""
        host, port = self.address
        return f"http://[{host}]:{port}/" if ":" in host else f"http://{host}:{port}/"

    def count(self, what: str) -> None:
        """Count a served or refused request."""
        self.counts[what] = self.counts.get(what, 0) + 1

    def start(self) -> None:
        """Serve in a background thread."""
        self._thread = threading.Thread(target=self._httpd.serve_forever,
                                        kwargs={"poll_interval": 0.25},
                                        name="display-http", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        """Stop serving and wake every live-feed writer."""
        self.stopping.set()
        if self._thread is not None:
            self._httpd.shutdown()
        self._httpd.server_close()
