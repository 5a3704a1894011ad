"""Decode AIS NMEA 0183 sentences (!AIVDM/!AIVDO, ITU-R M.1371 types 1/2/3/18/5/24) with pyais.

Times come from an NMEA 4.10 tag block (``\\c:<unix s>*hh\\``) or from a timestamp before the
sentence (ISO 8601 or unix seconds, separated by a space, comma or semicolon). Bad
checksums, garbage lines, incomplete multi-sentence messages, untimed lines and unsupported
message types are counted by reason, never silently dropped.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from datetime import UTC, datetime, timedelta
from decimal import Decimal, InvalidOperation
from functools import reduce
from pathlib import Path

from pyais import NMEAMessage

from ..errors import AisInputError
from .aistypes import NAN, AisFix, AisInput, AisStatic

POSITION_TYPES = frozenset({1, 2, 3, 18, 19})
STATIC_TYPES = frozenset({5, 24})
_TAG = re.compile(r"^\\([^\\]*)\\(.*)$")
_EPOCH = datetime(1970, 1, 1, tzinfo=UTC)
_MULTIPART_MAX_AGE = 10  # lines after which an unfinished multi-sentence message is dropped


def _nmea_checksum(text: str) -> int:
    return reduce(lambda a, c: a ^ ord(c), text, 0)


def parse_time_ns(text: str) -> int | None:
    """POSIX ns of a unix-seconds (or ms) number or an ISO 8601 time (naive = UTC), exact."""
    text = text.strip()
    try:
        value = Decimal(text)
    except InvalidOperation:
        try:
            dt = datetime.fromisoformat(text.replace("Z", "+00:00"))
        except ValueError:
            return None
        if dt.tzinfo is None:
            dt = dt.replace(tzinfo=UTC)
        return (dt - _EPOCH) // timedelta(microseconds=1) * 1000
    if not value.is_finite():
        return None
    if value > 10**11:  # milliseconds
        value /= 1000
    return int(value * 10**9)


def split_line(line: str) -> tuple[int | None, str, str]:
    """(time ns or None, sentence, problem) of one input line."""
    line = line.strip()
    m = _TAG.match(line)
    if m:
        tag, sentence = m.groups()
        body, _, check = tag.partition("*")
        if check and int(check, 16) != _nmea_checksum(body):
            return None, sentence, "tag_block_checksum"
        fields = dict(f.split(":", 1) for f in body.split(",") if ":" in f)
        return (parse_time_ns(fields["c"]) if "c" in fields else None), sentence, ""
    start = min((i for i in (line.find("!"), line.find("$")) if i >= 0), default=-1)
    if start < 0:
        return None, line, "garbage"
    prefix = line[:start].strip().rstrip(",;").strip()
    return (parse_time_ns(prefix) if prefix else None), line[start:], ""


def _fix(msg: dict, time_ns: int) -> AisFix:
    heading = msg.get("heading", 511)
    return AisFix(
        mmsi=int(msg["mmsi"]),
        time_ns=time_ns,
        lat_deg=float(msg.get("lat", 91.0)),
        lon_deg=float(msg.get("lon", 181.0)),
        sog_kn=float(msg.get("speed", 102.3)),
        cog_deg=float(msg.get("course", 360.0)),
        heading_deg=float(heading) if heading is not None else 511.0,
        nav_status=int(msg.get("status", 15)),
    )


def _static(msg: dict, time_ns: int) -> AisStatic | None:
    if msg["msg_type"] == 24 and "shipname" not in msg:
        return None  # type 24 part B carries no name/draught
    draught = float(msg.get("draught", 0.0) or 0.0)
    return AisStatic(
        mmsi=int(msg["mmsi"]),
        time_ns=time_ns,
        draught_m=draught if draught > 0 else NAN,  # 0 = not available
        name=str(msg.get("shipname", "") or "").strip("@ "),
        imo=int(msg.get("imo", 0) or 0),
    )


def decode_lines(lines: Iterable[str]) -> AisInput:
    """Decode NMEA lines into fixes and static records, counting every rejected line."""
    out = AisInput()
    pending: dict[tuple, tuple[int | None, int, list[NMEAMessage]]] = {}
    for lineno, raw in enumerate(lines):
        if not raw.strip():
            continue
        time_ns, sentence, problem = split_line(raw)
        if problem:
            out.rejected[problem] += 1
            continue
        try:
            nmea = NMEAMessage(sentence.encode("ascii"))
        except Exception:  # pyais raises several exception types on malformed text
            out.rejected["garbage"] += 1
            continue
        if not nmea.is_valid:
            out.rejected["checksum"] += 1
            continue
        if nmea.frag_cnt > 1:
            key = (nmea.seq_id, nmea.channel, nmea.frag_cnt)
            t0, _, parts = pending.get(key, (time_ns, lineno, []))
            parts.append(nmea)
            if len(parts) < nmea.frag_cnt:
                pending[key] = (t0, lineno, parts)
                continue
            pending.pop(key, None)
            time_ns = t0 if t0 is not None else time_ns
            try:
                nmea = NMEAMessage.assemble_from_iterable(sorted(parts, key=lambda p: p.frag_num))
            except Exception:
                out.rejected["bad_multipart"] += 1
                continue
        for key in [k for k, v in pending.items() if lineno - v[1] > _MULTIPART_MAX_AGE]:
            out.rejected["incomplete_multipart"] += len(pending.pop(key)[2])
        _add(out, nmea, time_ns)
    out.rejected["incomplete_multipart"] += sum(len(v[2]) for v in pending.values())
    if not out.rejected["incomplete_multipart"]:
        del out.rejected["incomplete_multipart"]
    return out


def _add(out: AisInput, nmea: NMEAMessage, time_ns: int | None) -> None:
    try:
        msg = nmea.decode().asdict()
    except Exception:
        out.rejected["undecodable_payload"] += 1
        return
    kind = msg.get("msg_type")
    if kind not in POSITION_TYPES and kind not in STATIC_TYPES:
        out.rejected["unsupported_type_" + str(kind)] += 1
        return
    if time_ns is None:
        out.rejected["no_timestamp"] += 1
        return
    if kind in POSITION_TYPES:
        out.fixes.append(_fix(msg, time_ns))
    else:
        static = _static(msg, time_ns)
        if static is not None:
            out.statics.append(static)


def read_nmea(path: str | Path) -> AisInput:
    """Decode an NMEA file (ASCII; undecodable bytes count as garbage lines)."""
    path = Path(path)
    try:
        with path.open("r", encoding="ascii", errors="replace") as f:
            return decode_lines(f)
    except OSError as exc:
        raise AisInputError(f"cannot read AIS NMEA file {path}: {exc}") from exc
