"""Open an OpenRocket ``.ork`` file and read values from its XML (numeric-only).

OpenRocket writes three containers: a zip archive whose first entry is the
XML (``rocket.ork``; decals and textures follow), a gzip stream (1.x) and
plain XML.  :func:`read_xml` detects the container from the magic bytes and
returns an :class:`Element` tree that knows its element path
(``rocket/subcomponents/stage[1]/subcomponents/bodytube[2]``), so every
error can name the element that is wrong.
"""
from __future__ import annotations

import gzip
import io
import math
import xml.etree.ElementTree as ET
import zipfile
import zlib
from pathlib import Path

from ironbark_opt.errors import InputError

#: file format versions this reader understands
SUPPORTED_VERSIONS = ("1.0", "1.1", "1.2", "1.3", "1.4", "1.5", "1.6", "1.7", "1.8", "1.9",
                      "1.10", "1.11")


class Element:
    """An XML element plus its path and the file it came from.

    Parameters
    ----------
    node : xml.etree.ElementTree.Element
    path : str
        Slash-separated element path below ``<openrocket>`` ("" for the root),
        with XPath-style 1-based indices among siblings of the same tag
        (always on components, the children of ``<subcomponents>``).
    source : str
        File name (for error messages).
    """

    def __init__(self, node: ET.Element, path: str, source: str):
        self.node = node
        self.path = path
        self.source = source

    @property
    def tag(self) -> str:
        return self.node.tag

    def error(self, message: str, child: str | None = None) -> InputError:
        """An InputError naming this element (or its ``child``)."""
        field = self.path if child is None else (f"{self.path}/{child}" if self.path else child)
        return InputError(message, source=self.source, field=field or "openrocket")

    def children(self, tag: str | None = None) -> list["Element"]:
        """Direct children (optionally only ``tag``), with their paths."""
        out, counts = [], {}
        nodes = [c for c in self.node if isinstance(c.tag, str)]
        totals: dict[str, int] = {}
        for c in nodes:
            totals[c.tag] = totals.get(c.tag, 0) + 1
        for c in nodes:
            counts[c.tag] = counts.get(c.tag, 0) + 1
            if tag is None or c.tag == tag:
                # components (children of <subcomponents>) always carry their index
                indexed = self.node.tag == "subcomponents" or totals[c.tag] > 1
                name = f"{c.tag}[{counts[c.tag]}]" if indexed else c.tag
                out.append(Element(c, f"{self.path}/{name}" if self.path else name, self.source))
        return out

    def child(self, tag: str) -> "Element | None":
        """The first direct child ``tag`` or None."""
        found = self.children(tag)
        return found[0] if found else None

    def require(self, tag: str) -> "Element":
        """The first direct child ``tag``; InputError naming the path if missing."""
        c = self.child(tag)
        if c is None:
            raise self.error(f"required element <{tag}> is missing in <{self.tag}>", tag)
        return c

    def text(self, tag: str, default: str | None = None) -> str | None:
        c = self.node.find(tag)
        if c is None or c.text is None:
            return default
        return c.text.strip()

    def has(self, tag: str) -> bool:
        return self.node.find(tag) is not None

    def number(self, tag: str, default: float | None = None, *, required: bool = False,
               minimum: float | None = None, auto: bool = False):
        """A number from child ``tag``.

        Parameters
        ----------
        tag : str
        default : float or None
            Returned when the element is absent (unless ``required``).
        required : bool
        minimum : float or None
            Smallest value accepted (e.g. 0 for lengths).
        auto : bool
            Accept ``auto`` (returns None) and ``auto 0.0125`` (returns the number).
        """
        raw = self.text(tag)
        if raw is None:
            if required:
                raise self.error(f"required element <{tag}> is missing in <{self.tag}>", tag)
            return default
        val = parse_number(raw, auto=auto, where=self, tag=tag)
        if val is not None and minimum is not None and val < minimum:
            raise self.error(f"<{tag}> must be >= {minimum:g}, got {val:g}", tag)
        return val

    def flag(self, tag: str, default: bool = False) -> bool:
        raw = self.text(tag)
        if raw is None:
            return default
        if raw.lower() not in ("true", "false"):
            raise self.error(f"<{tag}> must be true or false, got {raw!r}", tag)
        return raw.lower() == "true"

    def attr(self, name: str, default: str | None = None) -> str | None:
        return self.node.get(name, default)


def parse_number(raw: str, *, auto: bool = False, where: Element | None = None,
                 tag: str = "value"):
    """Parse OpenRocket's number text (``0.1``, ``NaN``, ``auto``, ``auto 0.0125``)."""
    text = raw.strip()
    if auto and text.lower().startswith("auto"):
        rest = text[4:].strip()
        if not rest:
            return None
        text = rest
    try:
        val = float(text)
    except ValueError:
        msg = f"<{tag}> must be a number{' or auto' if auto else ''}, got {raw!r}"
        if where is not None:
            raise where.error(msg, tag) from None
        raise InputError(msg, field=tag) from None
    if not math.isfinite(val):
        msg = f"<{tag}> must be finite, got {raw!r}"
        if where is not None:
            raise where.error(msg, tag)
        raise InputError(msg, field=tag)
    return val


#: Most bytes an .ork container may inflate to [B]: real OpenRocket designs are a few MB
#: (the largest of the OpenRocket examples inflates to under 10 MB); refuse zip/gzip bombs.
MAX_INFLATED_BYTES = 200 * 1024 * 1024


def _too_big(path, size=None) -> InputError:
    got = f" ({size / 2**20:.0f} MB)" if size is not None else ""
    return InputError(f"the container would inflate to more than {MAX_INFLATED_BYTES // 2**20} MB{got}; "
                      f"refused (real OpenRocket files inflate to a few MB)", source=path)


def _inflate_capped(stream, path) -> bytes:
    """Read a decompressing stream, refusing more than MAX_INFLATED_BYTES."""
    data = stream.read(MAX_INFLATED_BYTES + 1)
    if len(data) > MAX_INFLATED_BYTES:
        raise _too_big(path)
    return data


def read_bytes(path) -> bytes:
    """The XML bytes of an .ork file in any container (zip, gzip, plain)."""
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as err:
        raise InputError(f"cannot read file: {err.strerror}", source=path) from None
    if data[:4] == b"PK\x03\x04" or data[:2] == b"PK":
        try:
            with zipfile.ZipFile(io.BytesIO(data)) as zf:
                names = [n for n in zf.namelist() if not n.endswith("/")]
                if not names:
                    raise InputError("the zip archive is empty (expected the rocket XML as its "
                                     "first entry)", source=path)
                # OpenRocket writes the design as the first entry (rocket.ork)
                first = next((n for n in names if n.lower().endswith((".ork", ".xml"))), names[0])
                size = zf.getinfo(first).file_size
                if size > MAX_INFLATED_BYTES:
                    raise _too_big(path, size)
                with zf.open(first) as fh:        # the header may lie: cap the stream too
                    return _inflate_capped(fh, path)
        except (zipfile.BadZipFile, zlib.error, EOFError, KeyError) as err:
            raise InputError(f"damaged zip container (truncated or corrupt .ork): {err}",
                             source=path) from None
    if data[:2] == b"\x1f\x8b":
        try:
            with gzip.GzipFile(fileobj=io.BytesIO(data)) as fh:
                return _inflate_capped(fh, path)
        except (OSError, EOFError, zlib.error) as err:
            raise InputError(f"damaged gzip container (truncated or corrupt .ork): {err}",
                             source=path) from None
    return data


def read_xml(path) -> Element:
    """The root ``<openrocket>`` element of an .ork file (any container)."""
    data = read_bytes(path)
    try:
        root = ET.fromstring(data)
    except ET.ParseError as err:
        line = err.position[0] if getattr(err, "position", None) else None
        raise InputError(f"not well-formed XML: {err}", source=path, line=line) from None
    if root.tag != "openrocket":
        raise InputError(f"not an OpenRocket file: root element is <{root.tag}>, expected "
                         f"<openrocket>", source=path, field=root.tag)
    version = root.get("version", "")
    if version not in SUPPORTED_VERSIONS:
        raise InputError(f"OpenRocket file version {version or '(none)'} is not supported; "
                         f"expected one of {', '.join(SUPPORTED_VERSIONS)}", source=path,
                         field="openrocket/@version")
    return Element(root, "", str(path))
