"""OpenRocket ``.ork`` import.

Map of the package:

- :mod:`.xmlread` -- containers (zip / gzip / plain XML), element paths, numbers;
- :mod:`.components`, :mod:`.tree` -- the positioned component tree;
- :mod:`.ormass` -- mass, CG and inertia with OpenRocket's component rules;
- :mod:`.convert` -- OpenRocket components -> Ironbark geometry objects;
- :mod:`.motors` -- motor configurations and motor-file lookup;
- :mod:`.simdata` -- stored simulations: launch conditions and flight data;
- :mod:`.document` -- :func:`read_ork` -> :class:`OrkDocument`;
- :mod:`.build` -- :func:`load_ork` -> a flyable ``RocketFile``.
"""
from ironbark_opt.openrocket.build import load_ork
from ironbark_opt.openrocket.document import OrkDocument, read_ork
from ironbark_opt.openrocket.simdata import OrkSimulation

__all__ = ["OrkDocument", "OrkSimulation", "load_ork", "read_ork"]
