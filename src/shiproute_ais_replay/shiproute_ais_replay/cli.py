"""Bag tools: from-ais, simulate, record, info (rosbag2 MCAP)."""

from __future__ import annotations

import argparse
import json
import sys
from datetime import UTC, datetime
from pathlib import Path

from .errors import AisReplayError


def _iso(t_ns: int) -> str:
    return datetime.fromtimestamp(t_ns / 1e9, tz=UTC).isoformat().replace("+00:00", "Z")


def bag_info(path: str | Path) -> dict:
    """Topics, types, counts, time span, duration and size of a bag (no message decoding
    when metadata or an MCAP summary exists; otherwise a streaming scan)."""
    from .bag.bagreader import BagReader

    reader = BagReader(path)
    topics = reader.topics()
    if topics:
        t0, t1 = reader.time_span_ns()
        counts = {t.name: (t.typename, t.count) for t in topics}
        report = None
    else:  # no metadata and no summary (e.g. truncated): count by scanning
        counts, t0, t1 = {}, 2**63 - 1, 0
        for msg in reader.messages():
            typ, n = counts.get(msg.topic, (msg.typename, 0))
            counts[msg.topic] = (typ, n + 1)
            t0, t1 = min(t0, msg.time_ns), max(t1, msg.time_ns)
        report = reader.report()
    size = sum(f.stat().st_size for f in reader.files)
    out = {
        "path": str(path),
        "files": [str(f) for f in reader.files],
        "size_bytes": size,
        "message_count": sum(n for _, n in counts.values()),
        "start": _iso(t0) if counts else None,
        "end": _iso(t1) if counts else None,
        "duration_s": (t1 - t0) / 1e9 if counts else 0.0,
        "topics": [{"name": k, "type": v[0], "count": v[1]} for k, v in counts.items()],
    }
    if report is not None:
        out["scan"] = {k: v for k, v in report.items() if k != "problems"}
    return out


def _print_info(info: dict) -> None:
    print(f"bag:      {info['path']}  ({info['size_bytes'] / 1e6:.2f} MB)")
    print(f"span:     {info['start']} .. {info['end']}  ({info['duration_s']:.1f} s)")
    print(f"messages: {info['message_count']}")
    width = max((len(t["name"]) for t in info["topics"]), default=5)
    for t in info["topics"]:
        print(f"  {t['name']:<{width}}  {t['count']:>10}  {t['type']}")
    if "scan" in info:
        print(f"scan:     {info['scan']}")


def cmd_info(args: argparse.Namespace) -> int:
    """Print a bag's topics/types/counts/time span."""
    info = bag_info(args.bag)
    print(json.dumps(info, indent=2)) if args.json else _print_info(info)
    return 0


def cmd_from_ais(args: argparse.Namespace) -> int:
    """Convert NMEA or CSV AIS data to a bag and report what cleaning removed."""
    from .ais.ais_csv import read_csv
    from .ais.ais_nmea import read_nmea
    from .ais.aisbag import write_tracks
    from .ais.aisclean import clean

    src = Path(args.input)
    is_csv = args.format == "csv" or (args.format == "auto" and src.suffix.lower() == ".csv")
    data = read_csv(src) if is_csv else read_nmea(src)
    tracks, rejected, notes = clean(data, args.mmsi, args.max_speed_kn)
    if not tracks:
        print(f"no usable fixes in {src}; rejected: {dict(rejected)}", file=sys.stderr)
        return 1
    counts = write_tracks(tracks, args.output, with_fix=not args.no_fix)
    report = {
        "output": args.output,
        "vessels": [{"mmsi": t.mmsi, "name": t.name, "imo": t.imo, "fixes": len(t.states)}
                    for t in tracks],
        "fixes_read": len(data.fixes),
        "rejected": dict(rejected),
        "values_not_available": dict(notes),
        "messages_written": counts,
    }
    print(json.dumps(report, indent=2))
    return 0


def build_parser() -> argparse.ArgumentParser:
    """Argument parser of ``shiproute bag``."""
    ap = argparse.ArgumentParser(prog="shiproute bag", description=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("info", help="topics, types, counts, time span, size")
    p.add_argument("bag")
    p.add_argument("--json", action="store_true")
    p.set_defaults(func=cmd_info)
    p = sub.add_parser("from-ais", help="AIS NMEA or MarineCadastre CSV -> ShipState bag")
    p.add_argument("input")
    p.add_argument("output", help="bag directory (or .mcap file) to create")
    p.add_argument("--format", choices=("auto", "nmea", "csv"), default="auto")
    p.add_argument("--mmsi", type=int, default=None, help="only this vessel (own-ship topics)")
    p.add_argument("--max-speed-kn", type=float, default=50.0,
                   help="fixes implying a faster jump are rejected")
    p.add_argument("--no-fix", action="store_true", help="do not write NavSatFix")
    p.set_defaults(func=cmd_from_ais)
    from .simulate.simulate_cli import add_simulate_parser

    add_simulate_parser(sub)
    p = sub.add_parser("record", help="record live topics into a rosbag2 MCAP bag")
    p.add_argument("output")
    p.add_argument("topics", nargs="*", help="topics to record (default: all)")
    p.add_argument("--duration", type=float, default=0.0, help="stop after this many s")
    p.add_argument("--discovery-s", type=float, default=2.0,
                   help="re-scan the graph for new topics this often")
    p.set_defaults(func=lambda a: _record(a))
    return ap


def _record(args: argparse.Namespace) -> int:
    from .ros.record_node import record_main

    return record_main(args)


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``shiproute bag <sub> ...``."""
    args = build_parser().parse_args(argv if argv is not None else sys.argv[1:])
    try:
        return int(args.func(args))
    except AisReplayError as exc:
        print(f"shiproute bag {args.cmd}: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
