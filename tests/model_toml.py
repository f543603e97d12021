"""Rocket TOML of a wind-tunnel / range model (tests): a nose cone on a cylinder, optional
fins, a fixed mass, the data's moment reference as the CG and a motor file only to make
the file flyable (the aerodynamic tests never fly it)."""
from pathlib import Path

MOTOR = Path(__file__).parent / "data" / "motors" / "Cesaroni_M1670.eng"


def model_toml(name: str, *, calibre: float, nose_shape: str, nose_calibres: float,
               body_calibres: float, cg_x: float, shape_parameter: str = "", mass: float = 5.0,
               i_transverse: float = 0.5, i_axial: float = 0.01, extra: str = "",
               roughness: float | None = None) -> str:
    """The TOML text [m, kg]: nose ``nose_calibres`` long, cylinder ``body_calibres`` long
    (calibre ``calibre`` [m]), ``extra`` components after them (TOML text), the nozzle at
    the base; ``roughness`` [m] the [aero] surface roughness (None: the default)."""
    d = calibre
    param = f"shape_parameter = {shape_parameter}\n" if shape_parameter else ""
    aero = f"[aero]\nsurface_roughness = {roughness}\n" if roughness is not None else ""
    return f"""
[rocket]
name = "{name}"
[rocket.mass_override]
mass = {mass}
cg_x = {cg_x}
I_transverse = {i_transverse}
I_axial = {i_axial}
[[component]]
type = "nose_cone"
shape = "{nose_shape}"
{param}length = {nose_calibres * d}
radius = {d / 2}
[[component]]
type = "body_tube"
length = {body_calibres * d}
radius = {d / 2}
{extra}{aero}[motor]
file = "{MOTOR}"
nozzle_x = {(nose_calibres + body_calibres) * d}
[launch]
rail_length = 3.0
"""


def model_panel_geometry(folder, name: str, **kw):
    """(Rocket, panair RocketGeometry, symmetric) of :func:`model_toml` ``name`` with ``kw``,
    written to ``folder`` (a temp dir) and read back as ``aero build`` reads a rocket file."""
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.geometry_adapter import from_rocket, is_symmetric
    path = Path(folder) / f"{name.replace(' ', '_')}.toml"
    path.write_text(model_toml(name, **kw))
    rk, _ = load_rocket_geometry(path)
    geom = from_rocket(rk)
    return rk, geom, is_symmetric(geom)
