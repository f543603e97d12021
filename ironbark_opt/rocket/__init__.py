"""Rocket geometry, mass model and the rocket TOML format.

Map of the package:

- :mod:`.nose`, :mod:`.body` -- nose cones, body tubes, transitions (bodies of
  revolution on :mod:`.revolution`, shapes in :mod:`.shapes`);
- :mod:`.fins`, :mod:`.fin_sections` -- fin planforms and cross-sections;
- :mod:`.hardware` -- rail buttons, launch lugs, point masses, inner tubes;
- :mod:`.mass` -- MassProperties, symbolic-safe combination, wet/dry;
- :mod:`.materials` -- material densities and surface finishes;
- :mod:`.rocket` -- the Rocket;
- :mod:`.specs`, :mod:`.toml_io`, :mod:`.toml_write` -- launch-ready vehicle specs,
  the TOML reader and writer.

x [m] is measured aft from the nose tip everywhere.
"""
from ironbark_opt.rocket.body import BodyTube, Transition
from ironbark_opt.rocket.fin_sections import FinSection
from ironbark_opt.rocket.fins import EllipticalFins, FinSet, FreeformFins, TrapezoidalFins
from ironbark_opt.rocket.hardware import InnerTube, LaunchLug, PointMass, RailButtons, TubeFins
from ironbark_opt.rocket.mass import (MassProperties, combine, combine_properties,
                                      dry_from_wet, total_mass_properties)
from ironbark_opt.rocket.materials import FINISHES, MATERIALS, material_density
from ironbark_opt.rocket.nose import NoseCone
from ironbark_opt.rocket.rocket import Rocket
from ironbark_opt.rocket.specs import AeroSpec, BallastSpec, LaunchSpec, MotorSpec, RecoverySpec
from ironbark_opt.rocket.toml_io import RocketFile, load_rocket_toml, loads_rocket_toml
from ironbark_opt.rocket.toml_write import dump_rocket_toml, to_toml

__all__ = [
    "AeroSpec", "BallastSpec", "BodyTube", "EllipticalFins", "FINISHES", "FinSection", "FinSet",
    "FreeformFins", "InnerTube", "LaunchLug", "LaunchSpec", "MATERIALS", "MassProperties", "MotorSpec",
    "NoseCone", "PointMass", "RailButtons", "RecoverySpec", "Rocket", "RocketFile",
    "TrapezoidalFins", "Transition", "TubeFins", "combine", "combine_properties", "dry_from_wet",
    "dump_rocket_toml", "load_rocket_toml", "loads_rocket_toml", "material_density", "to_toml",
    "total_mass_properties",
]
