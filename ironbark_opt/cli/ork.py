"""``ironbark ork info FILE``: what an OpenRocket design holds (tree, masses, motors, simulations)."""
from __future__ import annotations

import click

from ironbark_opt.cli.common import emit, handle_errors, json_option


def ork_summary(doc, config: str | None = None) -> dict:
    """JSON-ready description of an :class:`OrkDocument` (unit-suffixed keys); numeric-only."""
    from ironbark_opt.openrocket import ormass
    from ironbark_opt.openrocket.document import nozzle_x

    dry = doc.dry_mass_properties()
    tree = []
    for comp, own, sub in ormass.component_table(doc.rocket.stages):
        depth = comp.path.count("/subcomponents/")
        tree.append({"depth": depth, "kind": comp.kind, "name": comp.name, "x_m": comp.x,
                     "length_m": comp.length, "mass_kg": own.mass, "subtree_mass_kg": sub.mass,
                     "cg_m": sub.cg_x})
    configs = []
    for c in doc.configs:
        configs.append({"id": c.config_id, "name": c.name, "label": c.label(), "default": c.default,
                        "motors": [{"designation": m.designation, "manufacturer": m.manufacturer,
                                    "delay_s": m.delay, "mount": mount.name,
                                    "count": mount.cluster_count,
                                    "nozzle_x_m": nozzle_x(mount, m),
                                    "ignition": m.ignition_event, "ignition_delay_s": m.ignition_delay,
                                    "stage": mount.stage} for mount, m in c.motors]})
    sims = []
    for s in doc.simulations:
        sims.append({"name": s.name, "config_id": s.config_id, **s.summary,
                     "rail_length_m": s.launch.rail_length,
                     "has_data": s.has_data(), "status": s.status})
    out = {"file": str(doc.path), "version": doc.version, "creator": doc.creator,
           "rocket": doc.name, "length_m": doc.length(), "dry_mass_kg": dry.mass,
           "dry_cg_m": dry.cg_x, "dry_inertia_transverse_kgm2": dry.I_transverse,
           "stages": len(doc.rocket.stages), "components": tree, "configurations": configs,
           "simulations": sims}
    out["stage_list"] = _stages(doc, config)
    from ironbark_opt.errors import InputError
    try:
        cfg = doc.config(config)
    except InputError:
        if config is not None:
            raise
        out.update(selected_config=None, launch_mass_kg=None, launch_cg_m=None,
                   launch_inertia_transverse_kgm2=None)
        return out
    out["selected_config"] = cfg.label()
    motors, files = [], []
    for mount, entry in cfg.motors:
        match = _find(doc, entry)
        files.append({"designation": entry.designation,
                      "file": None if match is None else str(match.path),
                      "digest_verified": None if match is None else match.verified})
        if match is None:
            motors = None
        elif motors is not None:
            it, ia = match.motor.inertia(0.0)
            motors.append((float(match.motor.mass(0.0)), float(match.motor.cg(0.0)),
                           float(it), float(ia)))
    out["selected_motors"] = files
    if motors is not None:
        launch = doc.launch_mass_properties(cfg, motors)
        out.update(launch_mass_kg=launch.mass, launch_cg_m=launch.cg_x,
                   launch_inertia_transverse_kgm2=launch.I_transverse)
    else:
        out.update(launch_mass_kg=None, launch_cg_m=None, launch_inertia_transverse_kgm2=None)
    return out


def _stages(doc, config: str | None) -> list:
    """One entry per axial stage: extent, dry mass, the selected configuration's
    motors and (lower stages) separation setting; numeric-only."""
    from ironbark_opt.errors import InputError
    from ironbark_opt.openrocket import ormass
    from ironbark_opt.openrocket.staging import _separation
    try:
        cfg = doc.config(config)
    except InputError:
        cfg = None
    out = []
    for i, st in enumerate(doc.rocket.stages):
        mp = ormass.rocket_mass([st], parallel=False)
        entry = {"index": i, "name": st.name, "x_m": st.x, "length_m": st.length, "dry_mass_kg": mp.mass,
                 "dry_cg_m": mp.cg_x, "motors": []}
        if cfg is not None:
            entry["motors"] = [{"designation": m.designation, "mount": mount.name, "ignition": m.ignition_event,
                                "ignition_delay_s": m.ignition_delay} for mount, m in cfg.motors if mount.stage == i]
            if i > 0:
                event, delay = _separation(st, cfg.config_id)
                entry.update(separation=event, separation_delay_s=delay)
        out.append(entry)
    for pod in doc.rocket.pods:                  # parallel boosters: all instances together
        from ironbark_opt.openrocket.parallel import separation
        mp = ormass.subtree_mass(pod)
        entry = {"index": pod.stage, "name": pod.name, "x_m": pod.x, "length_m": pod.length, "dry_mass_kg": mp.mass,
                 "dry_cg_m": mp.cg_x, "instances": pod.geo["instances"], "radial_distance_m": pod.geo["radius"],
                 "motors": []}
        if cfg is not None:
            entry["motors"] = [{"designation": m.designation, "mount": mount.name, "ignition": m.ignition_event,
                                "ignition_delay_s": m.ignition_delay} for mount, m in cfg.motors
                               if mount.stage == pod.stage]
            event, delay = separation(pod, cfg.config_id)
            entry.update(separation=event, separation_delay_s=delay)
        out.append(entry)
    return out


def _find(doc, entry):
    """The MotorMatch of an .ork motor, or None when no file is found (numeric-only)."""
    import warnings

    from ironbark_opt.errors import InputError
    from ironbark_opt.openrocket.motors import find_motor_file
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")       # reported as digest_verified = false
            return find_motor_file(entry.designation, entry.manufacturer, doc.path, entry.digest)
    except InputError:
        return None


def _human(info: dict) -> str:
    lines = [f"{info['rocket']}  ({info['file']}, format {info['version']})",
             f"length {info['length_m']:.4f} m, dry mass {info['dry_mass_kg']:.4f} kg, "
             f"dry CG {info['dry_cg_m']:.4f} m aft of the nose tip"]
    if info["launch_mass_kg"] is not None:
        lines.append(f"launch ({info['selected_config']}): mass {info['launch_mass_kg']:.4f} kg, "
                     f"CG {info['launch_cg_m']:.4f} m")
    elif info["selected_config"] is not None:
        lines.append(f"launch ({info['selected_config']}): a motor file is missing, no launch mass")
    for m in info.get("selected_motors", []):
        state = {True: "digest verified", False: "DIGEST DIFFERS", None: "digest not checked"}
        where = m["file"] or "not found"
        lines.append(f"  motor {m['designation']}: {where}"
                     f"{'' if m['file'] is None else ' (' + state[m['digest_verified']] + ')'}")
    lines.append(f"stages ({len(info['stage_list'])}):")
    for st in info["stage_list"]:
        motors = ", ".join(f"{m['designation']} in '{m['mount']}' on {m['ignition']} + {m['ignition_delay_s']:g} s"
                           for m in st["motors"]) or "no motor"
        sep = f"; separates on {st['separation']} + {st['separation_delay_s']:g} s" if "separation" in st else ""
        pods = (f" ({st['instances']} parallel boosters at {st['radial_distance_m']:.4f} m from the axis)"
                if "instances" in st else "")
        lines.append(f"  {st['index']}: {st['name']}{pods}, x = {st['x_m']:.4f}..{st['x_m'] + st['length_m']:.4f} m, "
                     f"dry {st['dry_mass_kg']:.4f} kg (CG {st['dry_cg_m']:.4f} m); {motors}{sep}")
    lines.append("components:")
    for c in info["components"]:
        lines.append(f"  {'  ' * c['depth']}{c['kind']:<16} {c['name'][:34]:<34} x={c['x_m']:.4f} m "
                     f"mass={c['mass_kg'] * 1000:.1f} g")
    lines.append("motor configurations:")
    for c in info["configurations"]:
        mark = "*" if c["default"] else " "
        lines.append(f" {mark} {c['id'][:8]}  {c['label']}")
    lines.append("simulations:")
    for s in info["simulations"]:
        apo = s.get("apogee_m")
        lines.append(f"   {s['name']}: apogee {apo if apo is not None else '-'} m"
                     f"{'' if s['has_data'] else ' (no stored data)'}")
    return "\n".join(lines)


@click.group("ork")
def ork_group():
    """OpenRocket .ork files."""


@ork_group.command("info")
@click.argument("file", type=click.Path(dir_okay=False))
@click.option("--config", "config", type=str, help="Motor configuration (id, name or designation).")
@json_option
@handle_errors
def info_command(file, config, as_json):
    """Show FILE's component tree, masses, CG, motor configurations and simulations."""
    from ironbark_opt.openrocket import read_ork
    info = ork_summary(read_ork(file), config)
    emit(info, as_json, _human(info))


COMMANDS = [ork_group]
