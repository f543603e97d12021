"""The Mach-box reference (tests/mach_box.py) against linear theory's closed forms, before
it serves as the reference for wings that have none (tests/unit/test_panair_low_aspect.py)."""
import numpy as np
import pytest
from scipy.special import ellipe

from mach_box import wing_cl_alpha


@pytest.mark.parametrize("mach, aspect", [(1.6, 2.0), (2.0, 1.0), (1.6, 1.0)])
def test_rectangular_wing_bonney(mach, aspect):
    # Bonney (J. Aero. Sci. 14, 1947): 4/B (1 - 1/(2 B A)) for B A >= 1
    b = np.sqrt(mach**2 - 1.0)
    ref = 4.0 / b * (1.0 - 1.0 / (2.0 * b * aspect))
    cla = wing_cl_alpha(lambda y: 0.0, lambda y: 1.0, aspect / 2.0, mach)
    assert abs(cla / ref - 1.0) < 0.015, (cla, ref)


@pytest.mark.parametrize("mach, cot_sweep", [(1.6, 0.5), (2.0, 0.5), (1.6, 1.0)])
def test_delta_wing_stewart(mach, cot_sweep):
    # Stewart (Quart. Appl. Math. 4, 1946): 2 pi cot(L) / E(k), k^2 = 1 - (B cot L)^2;
    # 4 / B for a supersonic (or sonic) leading edge
    b = np.sqrt(mach**2 - 1.0)
    m = b * cot_sweep
    ref = 2.0 * np.pi * cot_sweep / ellipe(1.0 - m * m) if m < 1.0 else 4.0 / b
    cla = wing_cl_alpha(lambda y: y / cot_sweep, lambda y: 1.0, cot_sweep, mach)
    assert abs(cla / ref - 1.0) < 0.015, (cla, ref)


def test_reverse_flow_theorem_swept_trailing_edge():
    """A parallelogram (subsonic swept leading and trailing edges at Mach 1.6, the wake
    acting on the wing) and the same wing in reversed flow have one CL-alpha (Brown,
    NACA TN 1944, 1949; Ursell & Ward 1950)."""
    c, s, t = 0.46, 0.098, 1.4
    le, te = (lambda y: t * y), (lambda y: c + t * y)
    x_end = c + t * s
    fwd = wing_cl_alpha(le, te, s, 1.6, n=60)
    rev = wing_cl_alpha(lambda y: x_end - te(y), lambda y: x_end - le(y), s, 1.6, n=60)
    assert abs(rev / fwd - 1.0) < 1e-3, (fwd, rev)
    # and a slender wing's lift is near pi A / 2 (slender-wing theory, R. T. Jones 1946)
    aspect = 4.0 * s * s / (2.0 * s * c)
    assert 0.8 < fwd / (np.pi * aspect / 2.0) < 1.3


def test_streamwise_tip_on_a_box_edge_converges():
    """A slender wing with a streamwise tip (B A = 0.33 at Mach 1.2): the boxed wing's span
    is the wing's (the tip on a box edge), so the box count changes its lift smoothly.
    Before session 19 the span was whole boxes about y = 0, up to half a box off the
    tip: n = 100 / 141 / 200 / 300 gave 0.834 / 0.758 / 0.798 / 0.786 /rad (lift ~ span^2),
    now 0.798 / - / 0.789 / 0.786."""
    le, te = (lambda y: 0.1373 / 0.0981 * y), (lambda y: 0.4593)
    a, b = (wing_cl_alpha(le, te, 0.0981, 1.2, n=n) for n in (100, 200))
    assert abs(a / b - 1.0) < 0.02, (a, b)
