"""``ironbark motor``: search ThrustCurve.org and download motor data files."""
from __future__ import annotations

import contextlib
import os
from pathlib import Path

import click

from ironbark_opt.cli.common import emit, handle_errors, json_option
from ironbark_opt.errors import InputError
from ironbark_opt.motors import thrustcurve as tc

offline_option = click.option("--offline", is_flag=True,
                              help="Use only the on-disk cache (no network).")


@contextlib.contextmanager
def offline_mode(enabled: bool):
    """Set ``IRONBARK_OFFLINE`` for the duration of one command."""
    if not enabled:
        yield
        return
    old = os.environ.get("IRONBARK_OFFLINE")
    os.environ["IRONBARK_OFFLINE"] = "1"
    try:
        yield
    finally:
        if old is None:
            os.environ.pop("IRONBARK_OFFLINE", None)
        else:
            os.environ["IRONBARK_OFFLINE"] = old


@click.group("motor")
def motor():
    """Motors from ThrustCurve.org (search, download RASP/RockSim files)."""


@motor.command("search")
@click.option("--designation", help="Manufacturer designation, e.g. K550W.")
@click.option("--common-name", help="Common name, e.g. K550.")
@click.option("--manufacturer", help="Manufacturer name or abbreviation, e.g. AeroTech.")
@click.option("--class", "impulse_class", help="Impulse class letter, e.g. K.")
@click.option("--diameter-mm", type=float, help="Motor diameter [mm], e.g. 54.")
@click.option("--type", "motor_type", type=click.Choice(["SU", "reload", "hybrid"]))
@click.option("--cert-org", help="Certification body (NAR, TRA, ...).")
@click.option("--availability", type=click.Choice(["regular", "occasional", "OOP",
                                                    "available", "all"]))
@click.option("--max-results", type=click.IntRange(min=1, max=1000), default=20, show_default=True)
@offline_option
@json_option
@handle_errors
def search_cmd(designation, common_name, manufacturer, impulse_class, diameter_mm, motor_type,
               cert_org, availability, max_results, offline, as_json):
    """Search ThrustCurve.org by designation, name, manufacturer, class or diameter."""
    if diameter_mm is not None and not 5.0 <= diameter_mm <= 500.0:
        raise InputError(f"expected a motor diameter of 5 to 500 mm, got {diameter_mm:g}", field="--diameter-mm")
    with offline_mode(offline):
        found = tc.search(designation=designation, common_name=common_name,
                          manufacturer=manufacturer, impulse_class=impulse_class,
                          diameter=None if diameter_mm is None else diameter_mm / 1000.0,
                          type=motor_type, cert_org=cert_org, availability=availability,
                          max_results=max_results)
    human = "\n".join(m.summary() for m in found) if found else "no motors match"
    emit({"count": len(found), "motors": [m.to_dict() for m in found]}, as_json, human)


def plot_thrust(motor, info: tc.MotorInfo, *, filename=None):
    """Thrust [N] vs time [s] of a parsed motor; returns the matplotlib figure."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, ax = plt.subplots(figsize=(7, 4))
    t = np.linspace(0.0, float(motor.burn_time) * 1.05, 400)
    ax.plot(t, np.asarray(motor.thrust(t), dtype=float).ravel())
    ax.set_xlabel("time [s]")
    ax.set_ylabel("thrust [N]")
    ax.set_title(f"{info.manufacturer_abbrev or info.manufacturer} {info.designation} "
                 "(ThrustCurve.org)")
    ax.grid(True, alpha=0.3)
    if filename is not None:
        fig.savefig(filename, dpi=100, bbox_inches="tight")
    return fig


def check_designation(designation: str) -> None:
    """A motor designation as ThrustCurve.org spells them (``K550W``, ``I216-CL``, ``1/4A3``,
    ``4263L1350-P``): letters, digits and ``-/._()+ ``; a file path is refused (exit 2)."""
    import re
    from ironbark_opt.errors import InputError
    text = (designation or "").strip()
    if not text:
        raise InputError("empty; give a motor designation such as K550W", field="designation")
    if "\\" in text or text.lower().endswith((".eng", ".rse", ".csv")) or text.startswith(("/", ".")):
        raise InputError(f"{text!r} is a file path; 'motor get' downloads by designation (e.g. K550W), "
                         "a motor file is given to simulate/ballast directly", field="designation")
    if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9 ._()+/-]{0,39}", text):
        raise InputError(f"{text!r} is not a motor designation (letters, digits and -/._()+, "
                         "e.g. K550W)", field="designation")


@motor.command("get")
@click.argument("designation")
@click.option("--manufacturer", help="Needed when several manufacturers use the name.")
@click.option("--format", "fmt", type=click.Choice(["RASP", "RockSim"]),
              help="Data-file format (default: certification data, RASP preferred).")
@click.option("-o", "--output-dir", type=click.Path(file_okay=False), default=".",
              show_default=True, help="Directory to write the motor file into.")
@click.option("--plot", is_flag=True, help="Also write a thrust-curve PNG next to the file.")
@offline_option
@json_option
@handle_errors
def get_cmd(designation, manufacturer, fmt, output_dir, plot, offline, as_json):
    """Download DESIGNATION's data file, write it and print a summary."""
    from ironbark_opt.cli.common import check_output_path
    check_designation(designation)
    check_output_path(output_dir, "--output-dir", directory=True)
    with offline_mode(offline):
        info, simfile = tc.fetch_motor_file(designation, manufacturer=manufacturer, format=fmt)
    path = tc.save_file(info, simfile, output_dir)
    result = info.to_dict()
    result.update(file=str(path), format=simfile.format, data_source=simfile.source,
                  simfile_id=simfile.simfile_id)
    lines = [info.summary(),
             f"wrote {path} ({simfile.format}, source: {simfile.source})"]
    if plot:
        try:
            parsed = tc.motor_from_text(simfile.text, simfile.format,
                                        designation=info.designation)
        except ImportError as err:
            raise InputError(f"cannot plot: the motor readers are not available ({err})",
                             field="--plot") from None
        png = Path(path).with_suffix(".png")
        plot_thrust(parsed, info, filename=png)
        result["plot"] = str(png)
        lines.append(f"plot: {png}")
    emit(result, as_json, "\n".join(lines))


COMMANDS = [motor]
