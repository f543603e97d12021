"""Bulk material densities and surface finishes.

Densities are bulk values [kg/m^3] for solids, fins and shells of a given
wall thickness.  Source: OpenRocket's built-in material database
(``core/.../database/Databases.java``, OpenRocket 23.09/24.12), which in turn
cites MatWeb data sheets and *Peak of Flight* newsletter issue 615.

Surface roughness heights [m] are OpenRocket's ``ExternalComponent.Finish``
values (equivalent sand-grain roughness).
"""
from __future__ import annotations

from ironbark_opt.errors import InputError

#: name -> bulk density [kg/m^3] (OpenRocket material database, see module docstring)
MATERIALS: dict[str, float] = {
    "aluminium": 2700.0,
    "balsa": 170.0,
    "basswood": 500.0,
    "birch": 670.0,
    "blue_tube": 1300.0,
    "brass": 8600.0,
    "cardboard": 680.0,
    "carbon_fibre": 1780.0,
    "fibreglass": 1850.0,
    "kraft_phenolic": 950.0,
    "pla": 1250.0,
    "abs": 1050.0,
    "plywood": 630.0,
    "quantum_tubing": 1050.0,
    "spruce": 450.0,
    "steel": 7850.0,
    "titanium": 4500.0,
}

#: American spellings accepted as aliases
_ALIASES = {"aluminum": "aluminium", "carbon_fiber": "carbon_fibre",
            "fiberglass": "fibreglass", "g10": "fibreglass", "plywood_birch": "plywood"}

#: finish name -> roughness height [m] (OpenRocket ExternalComponent.Finish)
FINISHES: dict[str, float] = {
    "rough": 500e-6,
    "rough_unfinished": 250e-6,
    "unfinished": 150e-6,
    "regular_paint": 60e-6,
    "smooth_paint": 20e-6,
    "optimum_paint": 5e-6,
    "polished": 2e-6,
    "finish_polished": 0.5e-6,
    "mirror": 0.0,
}
"""Roughness height [m] of OpenRocket's named surface finishes (OpenRocket
``ExternalComponent.Finish``, 23.09; Niskanen 2013 table 3.2 and Hoerner,
Fluid-Dynamic Drag, ch. 2 for the values)."""

#: OpenRocket's ``<finish>`` element values -> our finish names
ORK_FINISHES: dict[str, str] = {
    "rough": "rough", "roughunfinished": "rough_unfinished", "unfinished": "unfinished",
    "normal": "regular_paint", "smooth": "smooth_paint", "optimum": "optimum_paint",
    "polished": "polished", "finishpolished": "finish_polished", "mirror": "mirror",
}

#: default finish of every surface (regular paint, 60 um)
DEFAULT_ROUGHNESS = FINISHES["regular_paint"]


def material_density(name: str, *, source=None, line=None, field="material") -> float:
    """Bulk density [kg/m^3] of a named material (numeric-only).

    Parameters
    ----------
    name : str
        Material name, case-insensitive; spaces and hyphens count as ``_``.
    """
    key = str(name).strip().lower().replace(" ", "_").replace("-", "_")
    key = _ALIASES.get(key, key)
    if key not in MATERIALS:
        raise InputError(f"unknown material '{name}'; expected one of "
                         f"{', '.join(sorted(MATERIALS))} (or give density [kg/m^3])",
                         source=source, line=line, field=field)
    return MATERIALS[key]


def finish_roughness(name: str, *, source=None, line=None, field="finish") -> float:
    """Roughness height [m] of a named surface finish (numeric-only)."""
    key = str(name).strip().lower().replace(" ", "_").replace("-", "_")
    if key not in FINISHES:
        raise InputError(f"unknown finish '{name}'; expected one of {', '.join(FINISHES)}",
                         source=source, line=line, field=field)
    return FINISHES[key]
