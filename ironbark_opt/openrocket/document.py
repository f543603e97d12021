"""An opened .ork file: tree, mass build-up, configurations, simulations (numeric-only)."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ironbark_opt.errors import InputError
from ironbark_opt.openrocket import ormass
from ironbark_opt.openrocket.motors import MotorConfig, configurations, select_config
from ironbark_opt.openrocket.simdata import OrkSimulation, simulations
from ironbark_opt.openrocket.tree import OrkRocket, build_tree
from ironbark_opt.openrocket.xmlread import Element, read_xml
from ironbark_opt.rocket.mass import MassProperties, combine_properties


@dataclass
class OrkDocument:
    """Everything read from one .ork file.

    Parameters
    ----------
    path : Path
    version : str
        File format version (``1.0`` to ``1.11``).
    creator : str
    rocket : OrkRocket
        The positioned component tree.
    configs : list of MotorConfig
    simulations : list of OrkSimulation
    """

    path: Path
    version: str
    creator: str
    root: Element
    rocket: OrkRocket
    configs: list
    simulations: list

    @property
    def name(self) -> str:
        return self.rocket.name

    def length(self) -> float:
        """Nose tip to tail [m]."""
        return self.rocket.length()

    def dry_mass_properties(self) -> MassProperties:
        """All stages without motors, OpenRocket component rules (:mod:`.ormass`)."""
        return ormass.rocket_mass(self.rocket.stages)

    def config(self, wanted: str | None = None) -> MotorConfig:
        """A motor configuration by id / name / label / designation, or the configuration
        of the stored simulation named ``wanted`` (default: the file's)."""
        return self.config_and_simulation(wanted)[0]

    def config_and_simulation(self, wanted: str | None = None) -> tuple[MotorConfig, OrkSimulation | None]:
        """(motor configuration, the stored simulation whose launch conditions it flies).

        ``wanted`` is a configuration (id / name / label / designation: the first stored
        simulation of that configuration gives the launch conditions) or the exact name of
        a stored simulation (its configuration and its conditions: a design file often
        keeps one simulation per launch site, e.g. "Michiana - FT1", "Pence FT2").
        """
        if wanted is not None:
            named = [s for s in self.simulations if s.name.strip().lower() == wanted.strip().lower()]
            if named:
                sim = named[0]
                for c in self.configs:
                    if c.config_id == sim.config_id and c.motors:
                        return c, sim
                raise InputError(f"simulation {sim.name!r} flies motor configuration {sim.config_id!r}, which "
                                 "has no motor in the design", source=self.path, field="config")
        try:
            cfg = select_config(self.configs, wanted, self.path)
        except InputError as err:
            if wanted is None or not self.simulations:
                raise
            names = ", ".join(repr(s.name) for s in self.simulations[:8])
            raise InputError(f"{err.message}; or a stored simulation: {names}", source=self.path,
                             field="config") from None
        return cfg, self.simulation_for(cfg)

    def simulation_for(self, config: MotorConfig) -> OrkSimulation | None:
        """The first simulation flying ``config`` (else the first one), or None."""
        for s in self.simulations:
            if s.config_id == config.config_id:
                return s
        return self.simulations[0] if self.simulations else None

    def simulation(self, which: str | int | None = None) -> OrkSimulation:
        """A stored simulation by index or name (default: the first with flight data)."""
        if which is None:
            found = [s for s in self.simulations if s.has_data()] or self.simulations
        elif isinstance(which, int):
            found = self.simulations[which:which + 1] if -len(self.simulations) <= which < len(
                self.simulations) else []
        else:
            found = [s for s in self.simulations if s.name == which]
        if not found:
            names = ", ".join(repr(s.name) for s in self.simulations) or "none"
            raise InputError(f"no simulation {which!r}; the file has {names}", source=self.path,
                             field="simulations")
        return found[0]

    def flight_data(self, which: str | int | None = None):
        """OpenRocket's stored flight of one simulation as a DataFrame (``time_s``,
        ``altitude_m``, ``vertical_velocity_mps``, ...; :data:`.simdata.COLUMNS`), for
        overlaying on our :class:`~ironbark_opt.flight.Flight`; None if nothing is stored."""
        return self.simulation(which).data()

    def launch_mass_properties(self, config: MotorConfig, motor_masses) -> MassProperties:
        """Rocket plus loaded motors at t = 0.

        Parameters
        ----------
        config : MotorConfig
        motor_masses : sequence of (mass [kg], cg [m fwd of the nozzle exit],
            I_transverse [kg m^2], I_axial [kg m^2]), one per motor of ``config``
            in its order; each counts once per tube of a cluster.
        """
        items = [self.dry_mass_properties()]
        for (mount, entry), (m, cg, it, ia) in zip(config.motors, motor_masses):
            nozzle = nozzle_x(mount, entry)
            n = mount.cluster_count
            items.append(MassProperties.axisymmetric(n * m, nozzle - cg, n * it, n * ia))
        return combine_properties(items)


def nozzle_x(mount, entry) -> float:
    """Nozzle exit [m aft of the nose tip]: the motor's aft end sits at the mount's aft end
    plus the overhang (OpenRocket ``MotorMount.getMotorOverhang``)."""
    return mount.x + mount.length + mount.overhang


def read_ork(path) -> OrkDocument:
    """Open an .ork file (zip, gzip or plain XML; format 1.0-1.11) and read it.

    Raises InputError naming the element path for damaged or unsupported content.
    """
    path = Path(path)
    root = read_xml(path)
    tree = build_tree(root)
    return OrkDocument(path, root.attr("version", ""), root.attr("creator", ""), root, tree,
                       configurations(root, tree), simulations(root))
