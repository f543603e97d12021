"""``ironbark weather``: forecast, sounding and reanalysis profiles over a site."""
from __future__ import annotations

import math
from pathlib import Path

import click
import numpy as np

from ironbark_opt.atmosphere.base import wind_to_speed_direction
from ironbark_opt.atmosphere.levels import ProfileColumns
from ironbark_opt.atmosphere.sites import all_sites, get_site
from ironbark_opt.cli.common import emit, handle_errors, json_option
from ironbark_opt.cli.motor import offline_mode
from ironbark_opt.errors import InputError


@click.group("weather")
def weather():
    """Atmosphere profiles: NOAA RAP/GFS forecasts, UWyo soundings, ERA5 files."""


def plot_profile(col: ProfileColumns, *, filename=None):
    """Temperature, wind speed and wind direction vs altitude above ground.

    Returns the matplotlib figure; writes it to ``filename`` if given.
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    agl = (col.altitude - col.altitude[0]) / 1000.0
    speed, direction = wind_to_speed_direction(col.wind_east, col.wind_north)
    fig, axes = plt.subplots(1, 3, figsize=(11, 5), sharey=True)
    axes[0].plot(col.temperature, agl, "-o", ms=3)
    axes[0].set_xlabel("temperature [K]")
    axes[0].set_ylabel("altitude above ground [km]")
    axes[1].plot(speed, agl, "-o", ms=3)
    axes[1].set_xlabel("wind speed [m/s]")
    axes[2].plot(np.degrees(direction), agl, "o", ms=3)
    axes[2].set_xlabel("wind from [deg]")
    axes[2].set_xlim(0, 360)
    axes[2].set_xticks([0, 90, 180, 270, 360])
    for ax in axes:
        ax.grid(True, alpha=0.3)
    valid = "" if col.valid_time is None else f", valid {col.valid_time:%Y-%m-%d %H:%MZ}"
    fig.suptitle(f"{col.source}{valid}", fontsize=9)
    if filename is not None:
        fig.savefig(filename, dpi=100, bbox_inches="tight")
    return fig


def _summary(col: ProfileColumns, top_agl: float | None) -> str:
    def iso(t):
        return "-" if t is None else t.strftime("%Y-%m-%d %H:%MZ")
    lines = [f"source: {col.source}", f"run: {iso(col.run_time)}   valid: {iso(col.valid_time)}",
             f"ground: {col.altitude[0]:.0f} m ASL   levels: {col.altitude.size}"]
    lines += [f"note: {n}" for n in col.notes]
    lines.append(f"{'agl_m':>8} {'p_hPa':>8} {'T_K':>7} {'wind_mps':>9} {'from_deg':>8}")
    speed, direction = wind_to_speed_direction(col.wind_east, col.wind_north)
    for z, p, T, s, d in zip(col.altitude, col.pressure, col.temperature, speed,
                             np.degrees(direction)):
        if top_agl is not None and z - col.altitude[0] > top_agl:
            break
        frm = f"{d:8.0f}" if s >= 0.05 else f"{'calm':>8}"
        lines.append(f"{z - col.altitude[0]:8.0f} {p / 100:8.1f} {T:7.1f} {s:9.1f} {frm}")
    return "\n".join(lines)


@weather.command("get")
@click.option("--model", type=click.Choice(["rap", "gfs", "sounding", "reanalysis"]),
              default="rap", show_default=True, help="Data source.")
@click.option("--site", help="Launch-site preset (see `ironbark weather sites`).")
@click.option("--lat", "lat_deg", type=float, help="Site latitude [deg] (instead of --site).")
@click.option("--lon", "lon_deg", type=float, help="Site longitude [deg], east positive.")
@click.option("--elevation-m", type=float, help="Site ground elevation [m].")
@click.option("--time", "time_iso", help="Launch time, ISO 8601 UTC (e.g. 2025-06-20T15:00Z).")
@click.option("--station", help="Sounding station number (--model sounding).")
@click.option("--file", "path", type=click.Path(exists=True, dir_okay=False),
              help="Reanalysis netCDF or saved sounding file.")
@click.option("--top-m", type=float, default=15000.0, show_default=True,
              help="Print levels up to this height above ground [m].")
@click.option("--csv", "csv_path", type=click.Path(dir_okay=False),
              help="Write the profile as CSV (unit-suffixed columns).")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False),
              help="Write temperature/wind vs altitude plots to this PNG.")
@click.option("--out", "out_path", type=click.Path(dir_okay=False),
              help="Save the profile to fly offline later (simulate --atmosphere FILE): .json or .csv.")
@click.option("--offline", is_flag=True, help="Use only the on-disk cache (no network).")
@json_option
@handle_errors
def get_cmd(model, site, lat_deg, lon_deg, elevation_m, time_iso, station, path, top_m,
            csv_path, plot_path, out_path, offline, as_json):
    """Fetch a profile over a site and print it (optionally CSV, JSON, plot)."""
    from ironbark_opt.atmosphere.ncss import parse_iso
    from ironbark_opt.cli.common import PLOT_SUFFIXES, atomic_write, check_output_path
    check_output_path(csv_path, "--csv", (".csv", ".txt"))
    check_output_path(plot_path, "--plot", PLOT_SUFFIXES)
    check_output_path(out_path, "--out", (".json", ".csv"))
    for value, option, low, high in ((top_m, "--top-m", 0.0, 1e5), (lat_deg, "--lat", -90.0, 90.0),
                                     (lon_deg, "--lon", -180.0, 360.0), (elevation_m, "--elevation-m", -500.0, 9000.0)):
        if value is not None and not (low <= value <= high and (option != "--top-m" or value > 0)):
            raise InputError(f"must be a number in {'(' if option == '--top-m' else '['}{low:g}, {high:g}], "
                             f"got {value}", field=option)
    time = parse_iso(time_iso) if time_iso else None
    if site:
        s = get_site(site)
        lat, lon, elev = s.latitude, s.longitude, s.elevation
    elif lat_deg is not None and lon_deg is not None:
        lat, lon = math.radians(lat_deg), math.radians(lon_deg)
        elev = elevation_m
    else:
        lat = lon = elev = None
    with offline_mode(offline):
        if model in ("rap", "gfs"):
            if time is None:
                raise InputError("give --time (ISO 8601, UTC)", field="--time")
            if lat is None or elev is None:
                raise InputError("give --site, or --lat, --lon and --elevation-m", field="--site")
            from ironbark_opt.atmosphere.forecast import forecast_profile
            col = forecast_profile(model, time, latitude=lat, longitude=lon, elevation=elev)
        elif model == "sounding":
            from ironbark_opt.atmosphere import sounding
            if path:
                col = sounding.read_sounding(path)
            elif station and time is not None:
                col = sounding.fetch_sounding(station, time)
            else:
                raise InputError("give --station and --time, or --file", field="--station")
        else:
            from ironbark_opt.atmosphere.reanalysis import read_reanalysis
            if not path or lat is None:
                raise InputError("give --file and --site (or --lat/--lon)", field="--file")
            col = read_reanalysis(path, latitude=lat, longitude=lon, time=time,
                                  ground_elevation=elev)
    result = col.to_dict()
    if out_path:
        if str(out_path).lower().endswith(".json"):
            import json
            from ironbark_opt.cli.common import _clean
            text = json.dumps(_clean(result), indent=2)
            atomic_write(out_path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
        else:
            atomic_write(out_path, lambda tmp: col.to_dataframe().to_csv(tmp, index=False))
        result["out"] = str(out_path)
    if csv_path:
        atomic_write(csv_path, lambda tmp: col.to_dataframe().to_csv(tmp, index=False))
        result["csv"] = str(csv_path)
    if plot_path:
        atomic_write(plot_path, lambda tmp: plot_profile(col, filename=tmp))
        result["plot"] = str(plot_path)
    emit(result, as_json, _summary(col, top_m))


@weather.command("sites")
@json_option
@handle_errors
def sites_cmd(as_json):
    """List launch-site presets (built in and from the user config file)."""
    sites = all_sites()
    human = "\n".join(f"{s.name:20s} {s.latitude_deg:9.4f} {s.longitude_deg:10.4f} "
                      f"{s.elevation:7.0f} m  {s.description}" for s in sites.values())
    emit({"sites": [s.to_dict() for s in sites.values()]}, as_json, human)


COMMANDS = [weather]
