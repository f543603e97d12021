"""Aerodynamics: coefficient tables, skin friction and base drag.

- `table`: `AeroTable` (CSV + JSON files <-> SciPy / CasADi B-splines) and
  `GridSpline`, the interpolating spline both evaluate identically.
- `importers`: external tables (RocketPy/RASAero/OpenRocket Cd-vs-Mach, CFD).
- `friction_flatplate`: flat-plate skin friction (Blasius + Eckert, van Driest II,
  transitional composite, Barrowman roughness) and form factors.
- `friction`: `FrictionComponent`, `FrictionDrag` (component build-up, tabulated).
- `base_drag`: power-off / power-on base drag (`BaseDrag`, `cd_base`).
"""
from ironbark_opt.aero.base_drag import BaseDrag, cd_base
from ironbark_opt.aero.friction import FrictionComponent, FrictionDrag
from ironbark_opt.aero.friction_flatplate import (cf_flat_plate, cf_incompressible_turbulent,
                                                  cf_laminar_blasius, cf_roughness_limited,
                                                  cf_transitional, cf_turbulent_van_driest,
                                                  critical_reynolds_roughness, form_factor_body,
                                                  form_factor_fin)
from ironbark_opt.aero.importers import from_cd_mach_csv, from_coefficient_csv
from ironbark_opt.aero.table import AeroTable, GridSpline

__all__ = [
    "AeroTable", "BaseDrag", "FrictionComponent", "FrictionDrag", "GridSpline",
    "cd_base", "cf_flat_plate", "cf_incompressible_turbulent", "cf_laminar_blasius",
    "cf_roughness_limited", "cf_transitional", "cf_turbulent_van_driest",
    "critical_reynolds_roughness", "form_factor_body", "form_factor_fin",
    "from_cd_mach_csv", "from_coefficient_csv",
]
