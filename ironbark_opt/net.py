"""HTTP access to outside data: timeouts, retries, an on-disk cache, offline mode.

Every remote source (ThrustCurve.org, UCAR THREDDS, NOAA NOMADS and the NOAA
public cloud archives, the University of Wyoming sounding service) is reached
through :func:`fetch`, which

- takes its base URL from :func:`endpoint` (environment variable, then the
  user config file, then the built-in default), so no URL is buried in code;
- uses a connect/read timeout and retries connection failures, timeouts,
  truncated bodies and HTTP 5xx with exponential back-off (never HTTP 4xx);
- checks the body with the caller's ``parse`` function *before* caching it,
  so a malformed or truncated response never reaches the cache;
- writes the cache atomically (temporary file in the cache directory, then
  ``os.replace``), so an interrupted run never leaves a half-written file;
- falls back to the cached copy (with a warning) when the source is down,
  and in offline mode reads only the cache.

All functions here are numeric-only (I/O).  Network settings come from the
``[network]`` table of the user config file or from ``IRONBARK_OFFLINE``,
``IRONBARK_HTTP_TIMEOUT`` [s], ``IRONBARK_HTTP_RETRIES``,
``IRONBARK_HTTP_BACKOFF`` [s]; the cache lives in ``IRONBARK_CACHE_DIR``
(default: the platform's user cache directory, see :func:`cache_dir`).
"""
from __future__ import annotations

import hashlib
import json
import os
import sys
import tempfile
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable
from urllib.parse import urlencode

import requests

from ironbark_opt import config
from ironbark_opt.errors import InputError, NetworkError

#: name -> (environment variable, default base URL).  Paths below the base
#: URL are added by the clients.
ENDPOINTS: dict[str, tuple[str, str]] = {
    "thrustcurve": ("IRONBARK_THRUSTCURVE_URL", "https://www.thrustcurve.org/api/v1"),
    "thredds": ("IRONBARK_THREDDS_URL", "https://thredds.ucar.edu/thredds"),
    "nomads": ("IRONBARK_NOMADS_URL", "https://nomads.ncep.noaa.gov"),
    "gfs_archive": ("IRONBARK_GFS_ARCHIVE_URL", "https://noaa-gfs-bdp-pds.s3.amazonaws.com"),
    "rap_archive": ("IRONBARK_RAP_ARCHIVE_URL", "https://noaa-rap-pds.s3.amazonaws.com"),
    "uwyo": ("IRONBARK_UWYO_URL", "https://weather.uwyo.edu"),
}

_TRUE = {"1", "true", "yes", "on"}
_FALSE = {"0", "false", "no", "off"}


def endpoint(name: str) -> str:
    """Base URL of the named source, without a trailing slash.

    Looked up in order: environment variable (``ENDPOINTS[name][0]``), the
    ``[endpoints]`` table of the user config file, the built-in default.
    """
    if name not in ENDPOINTS:
        raise InputError(f"unknown endpoint {name!r}; expected one of {sorted(ENDPOINTS)}",
                         field="endpoints")
    env, default = ENDPOINTS[name]
    url = os.environ.get(env) or config.load().get("endpoints", {}).get(name) or default
    if not isinstance(url, str) or not url.startswith(("http://", "https://")):
        raise InputError(f"endpoint {name!r} must be an http(s) URL, got {url!r}",
                         source=env if os.environ.get(env) else config.config_path(),
                         field=f"endpoints.{name}")
    return url.rstrip("/")


@dataclass(frozen=True)
class NetSettings:
    """Timeout [s], retries [-], back-off base [s] and offline flag."""
    timeout: float = 20.0
    retries: int = 2
    backoff: float = 1.0
    offline: bool = False


def settings() -> NetSettings:
    """Network settings: environment variables override the config file."""
    net = config.load().get("network", {})
    try:
        timeout = float(os.environ.get("IRONBARK_HTTP_TIMEOUT", net.get("timeout_s", 20.0)))
        retries = int(os.environ.get("IRONBARK_HTTP_RETRIES", net.get("retries", 2)))
        backoff = float(os.environ.get("IRONBARK_HTTP_BACKOFF", net.get("backoff_s", 1.0)))
    except (TypeError, ValueError) as err:
        raise InputError(f"network settings must be numbers ({err})",
                         source=config.config_path(), field="network") from None
    env_off = os.environ.get("IRONBARK_OFFLINE")
    if env_off and env_off.strip().lower() not in _TRUE | _FALSE:
        raise InputError(f"expected one of {', '.join(sorted(_TRUE | _FALSE))}, got {env_off!r}",
                         field="IRONBARK_OFFLINE")
    offline = (env_off.strip().lower() in _TRUE) if env_off else bool(net.get("offline", False))
    if timeout <= 0 or retries < 0 or backoff < 0:
        raise InputError("timeout_s must be > 0, retries and backoff_s >= 0",
                         source=config.config_path(), field="network")
    return NetSettings(timeout, retries, backoff, offline)


def cache_dir() -> Path:
    """The on-disk cache directory (created on first write).

    ``IRONBARK_CACHE_DIR`` if set; otherwise ``$XDG_CACHE_HOME/ironbark`` or
    ``~/.cache/ironbark`` on Linux, ``~/Library/Caches/ironbark`` on macOS,
    ``%LOCALAPPDATA%\\ironbark\\Cache`` on Windows.
    """
    env = os.environ.get("IRONBARK_CACHE_DIR")
    if env:
        return Path(env).expanduser()
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "ironbark"
    if os.name == "nt":
        base = os.environ.get("LOCALAPPDATA") or str(Path.home() / "AppData" / "Local")
        return Path(base) / "ironbark" / "Cache"
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "ironbark"


def cache_key(url: str, params: dict | None = None, json_body: Any = None,
              byte_range: tuple[int, int | None] | None = None) -> str:
    """A stable file name for one request (SHA-256 of URL, query, body, range)."""
    text = url
    if params:
        text += "?" + urlencode(sorted((str(k), str(v)) for k, v in _param_items(params)))
    if json_body is not None:
        text += "\n" + json.dumps(json_body, sort_keys=True)
    if byte_range is not None:
        text += f"\nbytes={byte_range[0]}-{'' if byte_range[1] is None else byte_range[1]}"
    return hashlib.sha256(text.encode()).hexdigest()


def _param_items(params: dict):
    for k, v in params.items():
        if isinstance(v, (list, tuple)):
            for item in v:
                yield k, item
        else:
            yield k, v


def write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file and ``os.replace``.

    Readers see either the old file or the complete new one, never a
    half-written file, even if the process dies in the middle.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


@dataclass(frozen=True)
class Fetched:
    """One response: raw ``content``, the parsed ``data``, where it came from."""
    content: bytes
    data: Any
    url: str
    from_cache: bool
    status: int = 200
    headers: dict = field(default_factory=dict)


class _Retryable(Exception):
    pass


def _describe(url: str, params: dict | None) -> str:
    return url + ("?" + urlencode(list(_param_items(params))) if params else "")


def fetch(source: str, url: str, *, params: dict | None = None, json_body: Any = None,
          byte_range: tuple[int, int | None] | None = None,
          parse: Callable[[bytes], Any] | None = None, use_cache: bool = True,
          prefer_cache: bool = False, offline: bool | None = None,
          timeout: float | None = None, retries: int | None = None) -> Fetched:
    """GET (or POST ``json_body``) ``url`` and return the checked response.

    Numeric-only (I/O).

    Parameters
    ----------
    source : str
        Human name of the source for messages ("ThrustCurve.org", "THREDDS").
    url : str
        Full URL (build it from :func:`endpoint`).
    params : dict, optional
        Query parameters; list values repeat the key (``var=a&var=b``).
    json_body : any, optional
        If given, the request is a POST with this JSON body.
    byte_range : (int, int or None), optional
        HTTP ``Range: bytes=start-end`` (inclusive; None = to the end) [bytes].
    parse : callable(bytes) -> any, optional
        Checks and converts the body; raises :class:`InputError` when the body
        is malformed.  Runs before the body is cached.
    use_cache : bool
        Write successful responses to the cache and fall back to it.
    prefer_cache : bool
        Return a cached copy without asking the network (immutable data).
    offline : bool, optional
        Read only the cache (default from :func:`settings`).
    timeout : float, optional [s]
        Connect and read timeout (default from :func:`settings`).
    retries : int, optional
        Extra attempts after the first for retryable failures.

    Raises
    ------
    NetworkError
        The source failed (after retries) and no cached copy exists; the
        message names the URL and what to do.
    """
    cfg = settings()
    offline = cfg.offline if offline is None else offline
    timeout = cfg.timeout if timeout is None else timeout
    retries = cfg.retries if retries is None else retries
    parse = parse or (lambda b: b)
    key = cache_key(url, params, json_body, byte_range)
    cpath = cache_dir() / key[:2] / key
    shown = _describe(url, params)

    def from_cache() -> Fetched | None:
        if not use_cache or not cpath.is_file():
            return None
        content = cpath.read_bytes()
        try:
            data = parse(content)
        except InputError:
            return None
        return Fetched(content, data, shown, True)

    if offline or prefer_cache:
        hit = from_cache()
        if hit is not None:
            return hit
        if offline:
            raise NetworkError(
                f"{source}: offline mode and no cached copy of {shown}; "
                "run once online (unset IRONBARK_OFFLINE / drop --offline) to fill the cache")

    headers = {"User-Agent": "ironbark-opt (rocket apogee prediction)"}
    if byte_range is not None:
        end = "" if byte_range[1] is None else str(byte_range[1])
        headers["Range"] = f"bytes={byte_range[0]}-{end}"
    last = ""
    for attempt in range(retries + 1):
        if attempt:
            time.sleep(cfg.backoff * 2 ** (attempt - 1))
        try:
            resp = _request(url, params, json_body, headers, timeout)
            status = resp.status_code
            if status >= 500:
                raise _Retryable(f"HTTP {status} {resp.reason}")
            if status >= 400:
                last = f"HTTP {status} {resp.reason}"
                body = resp.text.strip().splitlines()
                if body and len(body[0]) < 200:
                    last += f" ({body[0]})"
                break
            content = resp.content
            if byte_range is not None and status == 200:
                # The server ignored Range and sent the whole file: cut it here.
                stop = None if byte_range[1] is None else byte_range[1] + 1
                content = content[byte_range[0]:stop]
            data = parse(content)
        except _Retryable as err:
            last = str(err)
            continue
        except requests.Timeout:
            last = f"no answer within {timeout:g} s (timeout)"
            continue
        except requests.ConnectionError as err:
            last = "connection failed (" + _short(err) + ")"
            continue
        except requests.RequestException as err:
            last = "transfer failed (" + _short(err) + ")"
            continue
        except InputError as err:
            last = f"malformed response: {err.message}"
            break
        if use_cache:
            write_atomic(cpath, content)
        return Fetched(content, data, shown, False, status, dict(resp.headers))

    hit = from_cache()
    if hit is not None:
        warnings.warn(f"{source}: {shown}: {last}; using the cached copy", stacklevel=2)
        return hit
    raise NetworkError(
        f"{source}: {shown}: {last}. Check the network and the endpoint "
        f"(set {_env_hint(url)}), retry later, or use --offline with a cached copy")


def _env_hint(url: str) -> str:
    """The environment variable whose endpoint ``url`` is under (the longest matching
    base); when several variables point at that same base, which one failed is not known
    here, so none is named."""
    hits = [(len(os.environ[env].rstrip("/")), env) for env, _ in ENDPOINTS.values()
            if os.environ.get(env) and url.startswith(os.environ[env].rstrip("/"))]
    longest = max((n for n, _ in hits), default=None)
    best = [env for n, env in hits if n == longest]
    if len(best) == 1:
        return best[0]
    if best:
        return f"the IRONBARK_*_URL variable of this source ({len(best)} point at this server)"
    return "the IRONBARK_*_URL variables"


def _short(err: Exception) -> str:
    text = str(err)
    if "Connection refused" in text:
        return "connection refused"
    if "IncompleteRead" in text or "incomplete" in text.lower():
        return "truncated body"
    return text[:160]


def _request(url, params, json_body, headers, timeout):
    if json_body is not None:
        return requests.post(url, params=params, json=json_body, headers=headers,
                             timeout=timeout)
    return requests.get(url, params=params, headers=headers, timeout=timeout)


def parse_json(source: str) -> Callable[[bytes], Any]:
    """A ``parse`` function for :func:`fetch` that decodes JSON or raises InputError."""
    def parse(content: bytes):
        try:
            return json.loads(content.decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as err:
            raise InputError(f"not valid JSON ({err})", source=source) from None
    return parse
