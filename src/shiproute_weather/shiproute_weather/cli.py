"""Forecast files and bundled scenarios: build, inspect, convert to canonical NetCDF."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from .errors import WeatherError


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="shiproute weather", description=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)
    sc = sub.add_parser("scenarios", help="list bundled scenarios, building missing files")
    sc.add_argument("names", nargs="*", help="scenario names (default: all)")
    sc.add_argument("--rebuild", action="store_true", help="regenerate even if cached")
    sc.add_argument("--list", action="store_true", help="only list, do not build")
    info = sub.add_parser("info", help="load files and describe the canonical dataset")
    info.add_argument("files", nargs="+")
    _member_options(info)
    conv = sub.add_parser("convert", help="load + combine + validate files, write canonical NetCDF")
    conv.add_argument("files", nargs="+")
    _member_options(conv)
    conv.add_argument("-o", "--output", required=True, help="output .nc path")
    conv.add_argument("--region", type=float, nargs=4,
                      metavar=("LAT_MIN", "LAT_MAX", "LON_MIN", "LON_MAX"),
                      help="cut to a box (LON_MAX may exceed 180)")
    return ap


def _member_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--as-members", action="store_true",
                   help="each FILE (or FILE+FILE...) is one member of a multi-model cycle "
                        "(regridded onto the first member's grid and valid times)")
    p.add_argument("--member-labels", default="",
                   help="comma-separated labels of the members (default: their sources)")


def _load(args: argparse.Namespace) -> Any:
    """The canonical dataset of the files: one cycle, or its members with --as-members."""
    from .ingest.loaders import open_forecast
    from .ingest.members import member_file_groups, open_members

    if args.as_members:
        labels = [x.strip() for x in args.member_labels.split(",") if x.strip()]
        return open_members(member_file_groups(args.files), labels)
    if args.member_labels:
        raise WeatherError("--member-labels needs --as-members")
    return open_forecast(args.files)


def _scenarios(args: argparse.Namespace) -> int:
    from .scenarios.catalogue import SCENARIOS, data_dir, scenario_path

    names = args.names or list(SCENARIOS)
    for n in names:
        spec = SCENARIOS.get(n)
        if spec is None:
            print(f"unknown scenario {n!r}; known: {', '.join(SCENARIOS)}", file=sys.stderr)
            return 2
        where = "" if args.list else f"  {scenario_path(n, rebuild=args.rebuild)}"
        print(f"{n:20s} {spec.reference_time}Z  {spec.description}{where}")
    if args.list:
        print(f"(files are built on first use into {data_dir() / 'scenarios'})")
    return 0


def _describe(args: argparse.Namespace) -> str:
    import numpy as np

    from .contract.canonical import VARIABLES, present_variables
    from .contract.members import member_count, member_labels
    from .contract.record import field_record, load_notes

    ds = _load(args)
    lat, lon, t = ds["latitude"].values, ds["longitude"].values, ds["time"].values
    lines = [f"cycle {ds.attrs['cycle_id']}  source {ds.attrs['source']}  reference "
             f"{ds.attrs['forecast_reference_time']}",
             f"grid {lat.size} x {lon.size}: lat {lat[0]:g}..{lat[-1]:g}, lon {lon[0]:g}.."
             f"{lon[-1]:g} (step {lat[1] - lat[0] if lat.size > 1 else 0:g} x "
             f"{lon[1] - lon[0] if lon.size > 1 else 0:g} deg)",
             f"times {t.size}: {str(t[0])[:16]}Z .. {str(t[-1])[:16]}Z"]
    if member_count(ds) > 1:
        lines.append(f"members {member_count(ds)} ({ds.attrs.get('member_kind', '')}): "
                     f"{', '.join(member_labels(ds))}")
    record = field_record(ds)
    for n in present_variables(ds):
        a = ds[n].values
        ok = np.isfinite(a)
        rng = f"{a[ok].min():9.3f} .. {a[ok].max():9.3f}" if ok.any() else "all NaN"
        rec = record[n]
        lines.append(f"  {n:45s} [{VARIABLES[n].units:6s}] {rng}  NaN {100 * (~ok).mean():.1f}%"
                     f"  <- {rec['source_variable']} of {Path(rec['source_file']).name}")
    lines += [f"note: {n}" for n in load_notes(ds)]
    return "\n".join(lines)


def _convert(args: argparse.Namespace) -> int:
    import numpy as np

    from .ingest.combine import Box, subset

    ds = _load(args)
    if args.region:
        ds = subset(ds, Box(*args.region))
    out = Path(args.output)
    ny, nx = ds.sizes["latitude"], ds.sizes["longitude"]
    enc = {n: {"zlib": True, "complevel": 4, "dtype": "float32",
               "chunksizes": (1,) * (ds[n].ndim - 2) + (ny, nx),
               "_FillValue": np.float32(np.nan)} for n in ds.data_vars}
    ds.to_netcdf(out, engine="netcdf4", encoding=enc)
    print(f"wrote {out} ({', '.join(str(n) for n in ds.data_vars)})")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of `shiproute weather ...`."""
    args = _parser().parse_args(sys.argv[1:] if argv is None else argv)
    try:
        if args.cmd == "scenarios":
            return _scenarios(args)
        if args.cmd == "info":
            print(_describe(args))
            return 0
        return _convert(args)
    except WeatherError as exc:
        print(f"shiproute weather: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
