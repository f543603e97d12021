"""CN-alpha of a model's fin panels alone, from the supersonic solver (panel-solver tests)."""
import numpy as np

from panair.solver import make_solver
from panair.solver.pressure import integrate_forces


def fin_panels_cn_alpha(panels, mach: float, sref: float, lref: float):
    """(CN-alpha [1/rad] of the fin panels (tip caps left out, as the solver's forces) on
    ``sref`` [m^2], from alpha 0 and 2 deg; the solver)."""
    s = make_solver(panels, mach, sref=sref, lref=lref)
    res = s.solve(np.radians([0.0, 2.0]))
    fins_id = np.unique(panels.network[panels.wake_upper[~panels.wake_at_base]])
    on = np.isin(panels.network[s._keep], fins_id) & ~s._caps
    cn = [integrate_forces(r.cp[s._keep][on], s._cen[on], s._nrm_f[on], s._area[on], sref=sref,
                           lref=lref, xref=0.0, symmetric=panels.symmetric)["CN"] for r in res]
    return (cn[1] - cn[0]) / np.radians(2.0), s
