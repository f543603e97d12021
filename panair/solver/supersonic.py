"""Supersonic linearised-potential panel solver (source panels, Mach-cone
domain of dependence).

Method: constant-strength source panels in the scaled space X = x / B
(B = sqrt(M^2 - 1)), Neumann mass-flux boundary condition on the wetted
side of every panel (Epton & Magnus, NASA CR-3251, sec. B.3; as in the
subsonic solver, the compressibility axis is the body x axis), with the
influence of each panel limited to its downstream Mach cone
(:mod:`.supersonic_influence`).  In supersonic flow a source distribution
represents the flow outside a closed body of revolution without doublets;
the base and its wake are downstream of everything that is integrated, so
they are left out (the linear theory is causal).  A fin's trailing-edge wake is
not, where the body continues behind the fin: it is solved as a two-faced source
sheet with the wake conditions (:mod:`.supersonic_wake`).  The mass flux through a
panel is the difference of the closed-form potential between a point on
its wetted side and a point one step further along the conormal
(-n_X, n_Y, n_Z) (a directional derivative); the tangential velocity
is the surface gradient of the potential, as in the
subsonic solver.

Regularisation: the wetted-side mass flux and the surface potential are
evaluated a small distance (FD_OFFSET x panel size) off the panel, with a
finite-difference step of the same size.  Constant-strength panels on a
smooth surface create Mach-line singularities along every panel edge (an
artefact of the discretisation); evaluated on the surface they make the
result depend on how the collocation point sits relative to the
neighbours' Mach lines (measured: ogive-cylinder CN-alpha varied by 6 %
for offsets 1e-6 ... 1e-4), 1-3 % off the surface the result is stable
(1e-2 ... 3e-2 within 0.3 %) and agrees with PANAIR's higher-order
(smooth-singularity) solution.

Fins (networks that shed trailing-edge wakes): with sources only, the two
faces of a thin fin nearly coincide and the lifting part of the system
becomes singular.  The two sides of a thin surface in supersonic flow are
independent, so a source on one side of a fin is not allowed to act on
the other side (:func:`_fin_shadow`); tip communication goes through the
tip cap.  This is an approximation of ours (validated against PANAIR on
the Basic Finner, tests/validation/test_panel_basic_finner_supersonic.py),
not PANAIR's doublet formulation.

Fin tip caps are part of the solution (the two sides of a fin communicate
through them) but not of the forces: linear theory puts corner
singularities on them (PANAIR too) while their true load is small (Basic
Finner: <= 0.9 % of CN-alpha); their Cp is still returned for plotting.

Nose correction: where linearised theory breaks on the nose (B tan delta
-> 0.5; the reference README shows PANAIR's nose load growing without
bound), forward-facing body panels take tangent-cone pressures
(:mod:`.nose_correction`), blended in smoothly over 0.4 < B tan delta < 0.6, each
panel by its own inclination delta (:data:`NOSE_WEIGHT_PER_PANEL`).

Checks that replace PANAIR's silent failures: every wetted panel must be
subinclined (its plane inclined to the flow by less than the Mach angle)
with a margin; Mach-inclined or superinclined panels, a singular system,
or a non-physical pressure (Cp below vacuum or above 1.5 x the stagnation
value on more than 1 % of the wetted area, or on a smaller area that carries
a non-negligible load, BAD_FORCE_MAX) raise SolverError naming the case.
Exception: compression beyond the bound on the leading-edge panels of a fin
edge that is sonic for linear theory (:func:`_sonic_leading_edge`), where the
theory's pressure is singular but integrable and its integrated load is the
theory's answer; they stay in the forces (``sonic_le_out_of_range`` records
that they left the range).

Numeric-only.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.errors import InputError, SolverError

from .panels import MirrorFold, PanelSet, mirror_plane
from .pressure import GAMMA, integrate_forces, pressure_coefficient, surface_gradient
from .subsonic import PanelResult, _free_stream, _refuse_sideslip
from .nose_correction import TangentCone
from .supersonic_influence import panel_frames, source_potential_pair
from .supersonic_diaphragm import diaphragm_sheets, merge_sheets, tip_sheets
from .supersonic_wake import (cut_wake_neighbours, fin_plane as _fin_plane, folded_wake_systems, sheet_geometry,
                              sheet_sides, sheet_twins, tip_caps as _tip_caps, wake_rows, wake_sheets)

__all__ = ["SupersonicSolver", "MACH_SUPERSONIC_MIN", "MACH_SUPERSONIC_MAX", "G1_MIN"]

MACH_SUPERSONIC_MIN = 1.2
MACH_SUPERSONIC_MAX = 5.0
NOSE_BLEND = (0.4, 0.6)
"""B tan(nose half-angle) over which nose pressures go from linear theory to
tangent-cone (smooth step)."""
NOSE_WEIGHT_PER_PANEL = True
"""True: each forward-facing body panel blends by its own B tan(delta) (the theory breaks
locally, where the surface is steep for the Mach cone); False: every nose panel by the
steepest one's, session 16.  The steepest is the tip ring of an ogive or Haack nose, a
sliver whose slope the mesh sets (the cosine-clustered first station, or the conical tip
of :func:`panair.mesh._sharpened_tip`), so the whole nose took tangent-cone pressures or
linear ones by the tip's mesh.  Measured (session 17; TR R-100 fineness-3 noses, Stoney's
free-flight pressure drag, each Mach number on its own tip, 24 points at Mach 1.2-3.4):
mean |error| 0.0124 -> 0.0045, largest 0.072 -> 0.021 (LV-Haack Mach 1.2 +0.072 -> +0.021,
1.4 +0.034 -> +0.006; von Karman 1.2 +0.043 -> +0.019, 1.4 +0.025 -> +0.002, 3.0 +0.002 ->
0.000; power 3/4 3.4 -0.008 -> 0.000); cones (every nose panel at one angle) unchanged."""
FD_OFFSET = 2e-2
FD_STEP = 2e-2
"""Finite-difference step for the normal mass flux, x sqrt(panel area) [-]."""
SIDE_TOL = 1e-6
"""Distance from a fin's mid-plane (and from the plane 90 deg from the fin)
below which a receiver is on neither side, x the model's largest extent [-]:
far above rounding (1e-16), far below a fin's half-thickness (1e-3 of the
model's size and more)."""
WAKE_SHEETS = True
"""Fin wakes behind which the body continues are part of the solve
(:mod:`.supersonic_wake`); False: the wall model before session 10 (for comparison)."""
THIN_WING = False
"""True: the thin-wing model of a fin pair in one plane, both parts of it —
coplanar partners sided (:func:`_fin_sides`) and diaphragms ahead of subsonic leading
edges (:mod:`.supersonic_diaphragm`).  It matches exact linear theory on a flat delta
wing on a thin body (tests/unit/test_panair_delta_wing.py: supersonic leading edge
-15 / -11 % -> within 0.5 %, subsonic -35 / -30 % -> converging to within 1-2 % of
Stewart's value).  Without the tip diaphragms (TIP_DIAPHRAGM, session 15) it raised
the supersonic CN-alpha of Allen's fin pairs, already above the tunnel's (fin 10 Mach
1.2 / 1.6 / 2.0 +31 / +22 / +14 % -> +53 / +32 / +22 %): a fin's plane was a wall
outboard of its tip, so a tip kept most of the two-dimensional lift (rectangular wing
A = 1, Mach 1.6: +24 % of Bonney's value), which the default model's partner leak (a
partner's lower-face sources cancelling the upper face's lift on a thin body: the
same wing -4 %) hid on thin bodies but not on a thick one.  Measured with both
(session 15): the wing alone of fin 10's exposed panels (thin body) 1.98 /rad at Mach
1.2 (slender-wing pi A / 2: 2.00; default model 2.49); on the body the fin-body factor
(fins + body lift) / wing alone 2.46 / 2.10 / 2.24 at Mach 1.2 / 1.6 / 2.0 (slender-body
K_W(B) + K_B(W) = 2.25; default model 3.96 / 2.80 / 2.57 against the same wing);
Allen's table CN-alpha fin 10 Mach 1.2 / 1.6 / 2.0 / 2.3 / 2.96 +31.4 / +21.5 / +14.0 /
+18.3 / +11.5 % -> -6.2 / +1.1 / +4.3 / +13.2 / +10.1 %, fin 12 +7.5 / +4.7 / -5.2 / +7.4 /
+7.8 -> -2.2 / +6.7 / -2.0 / +10.9 / +9.6 %, fin 1 (pointed tips, no tip diaphragm; the
leading-edge diaphragms add the subsonic edge's suction) +27.8 / +24.2 / +17.2 / +38.2 %
-> +25.1 / +27.6 / +23.0 / +43.8 % (its CP at Mach 2.3 +0.90 cal, past the test's 0.8
bound; fin 1 is as high subsonic, +22 / +32 %); Basic Finner vs PANAIR Mach 1.6 / 2.5
CN-alpha +0.9 / -3.1 -> -1.6 / -3.7 %, vs range data Mach 1.293 -5.8 -> -10.2 % (past
the 10 % bound; PANAIR's own linear theory is lower there too: Mach 1.2 PANAIR 18.60,
this model 17.92 (-3.7 %), the default 19.22 (+3.3 %); Cm-alpha -4.0 / +5.0 %).

Session 17: (a) the half model is the full one to rounding with it too
(tests/unit/test_panair_mirror.py: a half model's fin has its coplanar partner among the
mirror twins, :func:`_paired`); (c) the sheet faces are sided by :func:`_receiver_sides`
with the flag on or off (fin_plane's orientation made the two agree: LAPACK's sign had
sided whole wake sheets against their fins at some Mach numbers, a fault of the default
model too, see :func:`.supersonic_wake.fin_plane`).  (b) the sonic leading edge's CN at
Mach 1.2 (edge exactly sonic, m = B cot Lambda = 1) is -3.2 % of Mach 1.25's
(tests/unit/test_panair_supersonic_sonic.py, bound 3 %): a discretisation of the edge,
not physics.  At Mach 1.2 with the sweep varied, CN(2 deg) at m = 0.97 / 1.0 / 1.03 /
1.06: 0.633 / 0.641 / 0.656 / 0.656 (default 0.689 / 0.700 / 0.715 / 0.718, without
tip diaphragms 0.752 / 0.763 / 0.777 / 0.780): every model loses ~2 % at exactly m = 1,
where linear theory is flat (delta wing: 4 / B for every m >= 1).  The same on a flat
delta wing through its sonic edge (ours / exact, Mach 1.2 ... 1.4, m = 1 at Mach 1.3):
-10.4 / -10.1 / -9.5 / -7.0 / -2.6 / -1.3 / -0.5 % at m = 0.80 / 0.90 / 0.96 / 1.0 /
1.04 / 1.09 / 1.18 (the subsonic edge's sqrt(h) error, tests/unit/test_panair_delta_wing.py,
fading above m = 1).  No leading-edge diaphragm exists at m >= 1 (none switches at
Mach 1.2); the tip diaphragms make the Mach trend of the test's short fins flat
(CN(2 deg) Mach 1.2 / 1.25 / 1.3 / 1.4: 0.641 / 0.663 / 0.650 / 0.632; without them
0.763 / 0.749 / 0.715 / 0.664, falling like 4 / B), so the edge's dip shows; meshes
1 / 1.5 / 2 x: -3.2 / -2.3 / -3.3 %.

Measured flag off -> on (session 17, with the fixes): exact linear theory, flat delta
wing 45 deg Mach 1.6 / 2.0 -14.6 / -11.0 -> -0.5 / -0.1 %, 63.4 deg -35.2 / -30.3 ->
-9.8 / -9.9 % (-0.7 % extrapolated), Bonney's rectangular wing A = 2 Mach 1.6 / 2.0
-5.4 / -3.1 -> +2.8 / +2.4 %, A = 1 -9.0 / -7.5 -> +6.8 / +4.3 %; PANAIR, Basic
Finner CN-alpha / Cm-alpha Mach 1.2 +3.3 / +5.0 -> -3.4 / -3.7 %, 1.6 +0.9 / +2.0 ->
-1.6 / -1.9 %, 2.0 (ours at 2.02) -1.2 / -2.3 -> -2.4 / -4.6 %, 2.5 -3.1 / -3.0 -> -3.7
/ -4.6 %, 3.0 -6.3 / -1.8 -> -6.6 / -3.2 % (linear nose, as PANAIR); Allen's tunnel,
supersonic CN-alpha at the Mach numbers linear theory solves (1.2 ... 2.96), mean
|error| of fin sets 1 / 5 / 9 / 10 / 12: 26.9 / 18.9 / 14.6 / 19.3 / 6.5 -> 29.9 / 19.9
/ 19.2 / 7.0 / 6.3 % (all 16.8 -> 15.9 %), fin 1's CP at Mach 2.3 +0.69 -> +0.90 cal
(bound 0.8); Basic Finner range Mach 1.293 CN-alpha -5.8 -> -10.0 % (bound 10 %),
Cm-alpha +14.8 -> +8.1 %, 1.832 -1.1 -> -2.7 %, 2.375 -3.1 -> -3.9 %; its table vs
range within its bounds either way (Mach 1.077 CN-alpha -7.5 -> -10.0 %).  Defiance
(3 fins, leading edge 60 deg, span 0.82 cal) table CN-alpha / CP Mach 1.2 15.24 /
29.2 -> 10.23 / 25.8 cal, 1.5 13.89 / 27.7 -> 11.39 / 25.8, 2.0 13.80 / 26.4 -> 13.03
/ 25.8 (Mach 0.9 12.26 / 27.6 both), build 42 -> 47 s.  Better on the isolated wings,
not on PANAIR's Basic Finner (further from it at every Mach number from 1.6) nor in
the tunnel overall (fin 10 much better, fins 1, 5, 9 worse), and two bounds broken:
left off.

Session 18, against exact linear theory where no closed form exists (the Mach-box
method, tests/mach_box.py; tests/unit/test_panair_low_aspect.py): the default model's
supersonic excess on low-aspect-ratio fins is its missing communication around the fin
edges (the tips keep two-dimensional lift and hand it on to the body).  Allen's fin-10
pair (A 0.67) on its body, fins + interference, Mach 1.2 / 1.6 / 2.0: default +69.5 /
+21.8 / +14.2 %, this model +3.2 / -8.5 / -0.7 % (by part, default: fins +42 %, body
beside and behind them +118 % at Mach 1.2 against K_W(B) / K_B(W) x the wing); a random
rocket (4 parallelogram fins, pair A 0.43, r/s 0.44), fins + body beside and behind
them against the Mach-box wing x (1 + r/s)^2, Mach 1.2 / 1.6 / 2.0 / 2.3: default +62 /
+47 / +34 / +15 %, this model -15 / +5 / +4 / -6 % (rocket CN-alpha 12.73 / 12.98 /
12.98 / 12.44 -> 7.63 / 9.92 / 10.59 / 10.57 /rad; Mach 0.9 7.20).  That rocket had
every supersonic Mach number refused by this model: its fins lie partly over the
boattail, and the leading-edge diaphragm took the trailing edge's mid-plane stations
for leading-edge ones (fixed, :func:`.supersonic_diaphragm._fin_mid_plane`;
tests/unit/test_panair_diaphragm_stations.py); test_random_rockets passes with the flag
on.  Still short: very slender wings at Mach 1.2 (wing alone, B A ~ 0.3, unswept /
swept trailing edge) -21 / -28 % of the Mach box (default +33 / +34 %).  The tunnel
and range checks with the flag on are as measured in session 17 (Allen fin 1 Mach 2.3
+50.3 % against its 50 % regression bound, Basic Finner range Mach 1.293 -10.02 %
against 10 %): still off by default.

Session 19, the slender-wing shortfall: three causes, two of them numerics.  (1) The
reference: the Mach box's span was whole boxes about y = 0, up to half a box off a
streamwise tip (lift ~ span^2): the unswept-trailing-edge wing (B A 0.33) was 6 % high,
the parallelogram 5 % low at n = 100 (tip now on a box edge, tests/mach_box.py).
Against the corrected box the two were -20.5 / -31.2 %.  (2) The parallelogram's wake
sheets stopped beside the tip chord (the tip cap taken for the body by the sheets'
body-radius guard, :func:`.supersonic_wake.wake_sheets`; default model too, fins whose
tip runs aft of the root trailing edge; the default model on the parallelogram Mach 1.2 /
1.6 +29.0 / +23.3 -> +37.3 / +24.1 %): -31.2 -> -22.4 %.  (3) The leading-edge
diaphragm's cells were one median fin panel long, ~10 x the fin's cosine-clustered
leading-edge panel: graded to it (:data:`.supersonic_diaphragm.LE_GRADED`).  Thin-wing
vs the Mach box (n = 100), wing alone, before -> after: unswept TE Mach 1.2 / 1.6 / 2.0
-20.5 / +0.2 / +5.6 -> -11.3 / +4.9 / +5.6 %, parallelogram -31.2 / -9.8 / +4.2 -> -12.4 /
-3.1 / +4.2 %, Allen fin-10 pair -7.1 / -3.6 / -2.4 -> +1.9 / +2.6 / +1.8 %; delta 63.4 deg
Mach 1.6 on the supersonic meshes' cosine chordwise stations -7.9 -> -2.2 % (uniform:
-9.8 -> -7.3 %); fin 10 on its body (fins + interference vs wing x (1 + r/s)^2) +2.3 /
-6.8 / +0.2 -> +7.1 / -3.9 / +3.1 % (default +68 / +24 / +15 %).  The rest of the slender
wings' Mach 1.2 shortfall, about -10 % (the box at n = 100 is ~1.5 % above its limit),
is not discretisation of these parts: refine 1 / 1.4 / 2 -11.3 / -11.1 / -9.7 and -12.4 /
-10.9 / -10.4 %; finer tip diaphragms or fin strips toward the tip lower the lift (-2 %);
it sits at the tip's leading corner and in the aft (tip-induced) download.  Cost: fin 10
on its body, Mach 1.2 diaphragm cells 55 -> 127, solve 1.77 -> 1.95 s (default 1.34 s).
Validation flag off / on (after; before the grading in brackets): Allen supersonic
CN-alpha mean |error| (Mach 1.2-2.96, linear theory's) fin 1 28.1 / 32.3 (31.2), fin 5
20.5 / 21.6 (21.6), fin 9 16.0 / 22.1 (20.5), fin 10 21.3 / 9.2 (9.0), fin 12 7.2 / 6.9
(7.0), all 18.6 / 18.4 (17.9) %; fin 1 Mach 2.3 +44.7 / +50.3 % (bound 50 %: breaks), CP
+0.46 / +0.68 cal; Basic Finner (supersonic edges, unchanged by the grading) vs PANAIR
Mach 1.6 / 2.5 +0.9 / -3.1 -> -1.6 / -3.7 %, vs range Mach 1.293 -5.8 -> -10.02 % (bound
10 %: breaks), its table Mach 1.077 / 1.293 -8.4 / -3.8 -> -10.7 / -8.0 % (bounds hold).
Off by default: exact linear theory on the wings is better with it, the tunnel and
range data are not (fins 1 and 9, delta planforms, are above the tunnel with either
model and more so with it), and two regression bounds break."""
TIP_DIAPHRAGM = True
"""With THIN_WING: diaphragms outboard of the fin tips too
(:func:`.supersonic_diaphragm.tip_sheets`), where the upper and lower flows communicate
around a fin's side edge (the tip's lift loss of linear theory; Bonney's rectangular
wing, tests/unit/test_panair_tip_diaphragm.py).  False: the thin-wing model of session
12 (leading-edge diaphragms only), for comparison."""
TIP_DIAPHRAGM_DEFAULT = False
"""True: the tip diaphragms (:func:`.supersonic_diaphragm.tip_sheets`, Evvard NACA
Rep. 951) in the default model too (THIN_WING off: no leading-edge diaphragms, no
coplanar-partner siding; the tip sheet faces receive from their own fin's side only,
as the wake sheets).  Off by default: the tips alone over-correct.  Measured (session
15, default -> tips on): Bonney's rectangular wing on a thin body
(tests/unit/test_panair_tip_diaphragm.py) Mach 1.6 / 2.0, A = 2 -5.4 / -3.1 ->
-11.4 / -6.8 %, A = 1 -9.0 / -7.5 -> -24.4 / -17.6 % (THIN_WING with the tips: +2.8 /
+2.4, +6.8 / +4.3 %); Allen's table CN-alpha fin 10 Mach 1.2 / 1.6 / 2.0 / 2.3 /
2.96 +31.4 / +21.5 / +14.0 / +18.3 / +11.5 -> -20.8 / -7.2 / -1.8 / +7.3 / +7.0 %, CP
+0.55 / +0.17 / +0.01 / +0.20 / +0.18 -> -0.90 / -0.73 / -0.53 / -0.16 / +0.03 cal
(fin 10's 0.8 cal bound broken at Mach 1.2), fin 12 +7.5 / +4.7 / -5.2 / +7.4 / +7.8 ->
-8.9 / +1.8 / -6.2 / +6.7 / +7.5 %, fin 5 Mach 1.2 / 1.6 / 2.0 +35.5 / +19.0 / +7.4 ->
+23.9 / +16.3 / +6.6 %, fins 1 and 9 (pointed tips) unchanged; Basic Finner vs PANAIR
Mach 1.6 / 2.5 CN-alpha +0.9 / -3.1 -> -1.9 / -3.8 %, Cm-alpha +2.0 / -3.0 -> -2.4 /
-5.1 % (bound 5 %), vs range data Mach 1.293 CN-alpha -5.8 -> -11.4 % (bound 10 %),
the table vs range Mach 1.077 -10.3 -> -13.0 % (bound 13 %); cone-cylinder, the sonic
leading edge (Mach 1.2 / 1.25 CN 0.5948 / 0.6103, -2.5 %) and the half / full model
(tests/unit/test_panair_mirror.py) pass.  The tips take about the same lift off as in
the thin-wing model (fin 10 Mach 1.2: -4.3 /rad here, -4.9 there) but the default
model starts lower: its partner leak (:func:`_fin_sides`, a coplanar partner's
lower-face sources acting on the upper face) partly cancelled the wall outboard of
the tip, so the tips need the partner siding of THIN_WING with them.  Measured so
(THIN_WING's partner siding and the tips, its leading-edge diaphragms left out): fin 10
Mach 1.2 / 1.6 / 2.0 -13.3 / -3.8 / +3.1 %, CP -0.63 / -0.63 / -0.33 cal (within its
bound), fin 12 and the Basic Finner as THIN_WING (supersonic leading edges), fin 5
+26.4 / +21.7 / +11.9 %; the Basic Finner vs range Mach 1.293 -10.2 % still breaks the
10 % bound, as with THIN_WING: every variant with the tips does (PANAIR, linear theory
too, is 3 % below the default at Mach 1.2)."""
G1_MIN = 0.05
"""Minimum 1 - 2 n_X^2 (scaled coordinates) of a wetted panel: below it the
panel is (nearly) Mach-inclined and linear theory has no valid solution."""


BAD_AREA_MAX = 0.01
"""Largest fraction of the wetted area allowed with Cp beyond vacuum or 1.5 x
stagnation (isolated corner singularities at fin tips are tolerated, as
they are local and negligible in the integrated forces)."""
BAD_FORCE_MAX = 0.01
"""Smallest tolerance on the load of the out-of-range panels, as a force
coefficient (moments: the same times the moment arm, max |x - xref| / lref);
see BAD_FORCE_FRACTION for the tolerance actually applied.  Measured on
the validated Basic Finner cases (Mach 1.29-4.3, alpha <= 4 deg): <= 0.0014 in
CN and <= 0.0068 in Cm (tolerance 0.05 there).  Cases the area rule alone let
through: a Mach-cone coincidence on a tip cap (Cp ~ -2e8 on 0.01 % of the
area, CN ~ 9e5; caps are no longer integrated, CAP_CP_MAX reports it); rounded (blunt) fin leading edges at Mach 1.2-1.3 (Cp below
vacuum on 0.4 % of the area carrying CA -0.15 at alpha 0 and 22 % of CN at
alpha 4 deg)."""
CLIP_AREA_MAX = 2.5e-3
"""Out-of-range panels that cover at most this fraction of the wetted area and carry
more than the tolerance (:data:`BAD_FORCE_FRACTION`) but at most :data:`CLIP_LOAD_MAX`
times it are a local singularity of linear theory (a fin tip's corners, a near-sonic
edge, a sliver): their pressure is clipped to the physical bounds (vacuum, 1.5 x
stagnation) and the solution kept (``cp_clipped``; the sweep lists such Mach numbers
in ``mach_cp_clipped``) instead of the whole Mach number falling to local inclination
(no fin-body carry-over).  Measured (session 17, 24 random student rockets, every
supersonic Mach of the default grid): 6 of them had a Mach number refused; on four
the out-of-range panels covered 0.001-0.09 % of the area with 1.0-4.2 x the tolerated
load, and the clipped solution follows the Mach trend of the cleanly solved neighbours
better than local inclination does, e.g. CN-alpha (CN at 4 deg) at Mach 1.2 / 1.25 / 1.3:
clipped 15.9 / 15.7 / 15.1, local inclination 22.7 / 21.5 / 19.3 /rad, Mach 1.5 solved
cleanly 13.5 /rad; another rocket at Mach 1.45 / 1.5 / 1.55 (sonic fin edge): clipped
16.0 / 16.6 / 16.5, local inclination 16.3 / 15.9 / 15.0, Mach 1.6 cleanly 16.0 /rad, CA0
clipped 0.153 / 0.147 / 0.145 on the trend to 0.142, local inclination 0.167 / 0.160 /
0.155.
A breakdown spread over more area (0.84 % at 5-8 x the load, Mach 1.9-2.1, a cone
nose with rounded fins) clipped erratically (CN(4 deg) 0.55 / 0.56 / 0.81 / 0.63 /
0.61) and stays refused."""
CLIP_LOAD_MAX = 5.0
"""See :data:`CLIP_AREA_MAX`."""
CAP_CP_MAX = 1e4
"""Largest |Cp| tolerated on the (not integrated) fin tip caps: corner
singularities reach ~1e3 (measured: Basic Finner 579, Kestrel 848 at Mach 1.5,
alpha 12 deg); a Mach-cone coincidence on a cap gives ~1e8 and moves the
integrated solution too (pitched Basic Finner, Mach 2.375: lift +11 %)."""
CLOSURE_PHI_RATIO = 10.0
"""Largest |potential| on the closure slivers of a pointed fin tip
(:func:`_pointed_tip_closure`) as a multiple of the largest elsewhere: a
Mach-cone coincidence makes it singular, a regular solution keeps it within
the fin's own range."""
BAD_FORCE_FRACTION = 0.01
"""The out-of-range panels may carry at most max(BAD_FORCE_MAX,
BAD_FORCE_FRACTION x the largest force coefficient of the in-range panels).
Corner singularities grow with the flow angle like the whole solution, so
the tolerance has a relative part (measured: fin-tip-cap trailing-edge corners
of the Basic Finner at Mach 1.2, alpha 10 deg carry 0.011 of CN = 3.25)."""


class CausalLU:
    """LU factorisation of a supersonic influence matrix, kept sparse by causality.

    A source acts only inside its downstream Mach cone, so with the panels
    ordered by (scaled) x the matrix is lower triangular but for the few pairs
    at the same station (measured: 0.04 % of the non-zeros above the diagonal,
    two thirds of all entries zero, on a 5269-panel rocket at Mach 1.5).  A
    sparse LU (SuperLU, partial pivoting, the columns kept in that order) then
    has almost no fill-in: the same solution as the dense LU to rounding
    (measured 3e-15 relative) in a third of its time.

    Parameters
    ----------
    A : ndarray (n, n)
        The influence matrix (not modified).
    x : ndarray (n,)
        Collocation x coordinate of each row/column [m] (any monotone scaling).
    """

    def __init__(self, A: np.ndarray, x: np.ndarray):
        from scipy.sparse import csc_matrix
        from scipy.sparse.linalg import splu

        from .kernels import HAVE_NUMBA, dense_to_csc
        self._order = np.argsort(x, kind="stable")
        o = self._order
        n = len(o)
        if HAVE_NUMBA:                # the permuted CSC in two passes (scipy: ~10 x longer)
            sparse = csc_matrix(dense_to_csc(np.ascontiguousarray(A, float), o), shape=(n, n))
        else:
            sparse = csc_matrix(A)[o][:, o].tocsc()
        try:
            self._f = splu(sparse, permc_spec="NATURAL")
        except RuntimeError as exc:          # SuperLU: "Factor is exactly singular"
            raise SolverError(f"singular supersonic influence matrix ({exc})") from exc

    def pivots(self) -> np.ndarray:
        """|diagonal of U| (for the singularity check)."""
        return np.abs(self._f.U.diagonal())

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """A^-1 rhs for rhs (n,) or (n, k)."""
        out = np.empty_like(rhs, dtype=float)
        out[self._order] = self._f.solve(np.ascontiguousarray(rhs[self._order], dtype=float))
        return out


def _bad_panels(cp, cp_vac, cp_max):
    return ~np.isfinite(cp) | (cp < cp_vac - 0.05) | (cp > cp_max)


def _bad_area(cp, area, cp_vac, cp_max):
    bad = _bad_panels(cp, cp_vac, cp_max)
    return float(area[bad].sum() / max(area.sum(), 1e-300))


def _fin_shadow(panels: PanelSet, keep, cen, nrm) -> np.ndarray:
    """Source-receiver pairs separated by a fin (m, m): True where panel j's source
    must not act on panel i's collocation point (:func:`_fin_sides` as a mask)."""
    recv, src_fin, src_side = _fin_sides(panels, keep, cen, nrm)
    if not len(recv):
        return np.zeros((len(src_fin), len(src_fin)), bool)
    return (src_fin[None, :] >= 0) & (recv[np.maximum(src_fin, 0)].T * src_side[None, :] < 0)


def _fin_sides(panels: PanelSet, keep, cen, nrm):
    """Which source-receiver pairs a fin separates, as sides: ``recv`` (n_fins, m)
    the side of fin f each receiver is on (+-1, 0 none), ``src_fin`` (m,) the fin a
    source panel is a face of (-1 none) and ``src_side`` (m,) that face's side;
    panel j's source does not act on panel i when recv[src_fin[j], i] *
    src_side[j] < 0.

    A fin is a network that sheds a trailing-edge wake.  Its mid-plane
    (least-squares plane through its panel centroids) splits space; a face
    panel belongs to the side its normal points to (tip caps and edges to
    neither).  Receivers are the fin's own faces and the body panels in the
    fin's half of the cross-section downstream of its leading edge; a source on one side of the fin does
    not act on a receiver on the other side.  This is the thin-wing
    property of supersonic flow (the two sides of a thin surface are
    independent, e.g. Ward 1955, ch. 8) imposed on the thick panel model,
    where the two faces of a thin fin would otherwise nearly coincide and
    make the system singular.  Tip-region communication around the fin tip
    goes through the tip cap.

    With THIN_WING (off by default, see there): a fin's coplanar partner (the fin
    opposite it, 180 deg in roll: one plane through the axis, :func:`_coplanar`) is
    part of the same thin surface: its faces are receivers on the side they face, and
    the plane through both splits the whole body (not only the fin's half).  Without
    that, near a thin body (a flat wing: two fins on a thin body), a source on the
    lower face of one fin acts on the upper face of the other and cancels most of the
    upper face's own source there (the two nearly coincide): a flat delta wing with a
    supersonic leading edge has CN-alpha 11-15 % below exact linear theory (4 / B),
    within 0.5 % with the partner sided (tests/unit/test_panair_delta_wing.py).  In thin-wing theory the upper
    half-space is influenced by the sources of the upper side of the whole plane
    only (e.g. Ward 1955, sec. 8.2; Jones & Cohen, *High Speed Wing Theory*, 1960,
    sec. 5); PAN AIR gets the same from its doublet sheets, whose potential
    vanishes in their own plane outside the sheet (Epton & Magnus, NASA CR-3251).

    Sides are decided with a tolerance, SIDE_TOL x the model's size, not by the
    sign of rounding noise: a receiver within it of the fin's mid-plane (the tip
    cap panels, whose centroids lie on it) is on neither side and receives from
    both faces; a body panel within it of the plane through the axis
    perpendicular to the fin (90 deg from it) is not in the fin's half.  The
    assignment is then deterministic and a mirror-symmetric model's is its own
    mirror image.
    """
    net = panels.network[keep]
    m = len(net)
    src_fin = -np.ones(m, np.int64)
    src_side = np.zeros(m)
    lifting = ~panels.wake_at_base
    if not np.any(lifting):
        return np.zeros((0, m)), src_fin, src_side
    fins = np.unique(panels.network[panels.wake_upper[lifting]])
    fin_r = _fin_index(panels, keep)
    planes, x0, tol = _fin_planes(panels, keep, cen, fins)
    partner = _partners(planes, tol)
    recv = _receiver_sides(planes, x0, tol, partner, cen, nrm, fin_r, _paired(panels, planes, tol))
    for k in range(len(fins)):
        own = (fin_r == k) & (recv[k] != 0)
        src_fin[own] = k
        src_side[own] = recv[k, own]
    return recv, src_fin, src_side


def _fin_index(panels: PanelSet, keep) -> np.ndarray:
    """Per kept panel, the index of the fin (network shedding a trailing-edge wake,
    in sorted network order) it is a panel of, -1 none."""
    net = panels.network[keep]
    lifting = ~panels.wake_at_base
    fins = np.unique(panels.network[panels.wake_upper[lifting]]) if np.any(lifting) else []
    return np.where(np.isin(net, fins), np.searchsorted(fins, net), -1)


def _fin_planes(panels: PanelSet, keep, cen, fins):
    """Per fin (``fins`` order): its mid-plane (point, unit normal,
    :func:`panair.solver.supersonic_wake.fin_plane`), its leading x (min of its
    panels' collocation x) and the side tolerance (SIDE_TOL x the model's size)."""
    net = panels.network[keep]
    planes = [_fin_plane(cen[net == f]) for f in fins]
    x0 = np.array([cen[net == f, 0].min() for f in fins])
    return planes, x0, SIDE_TOL * float(np.ptp(cen, axis=0).max())


def _coplanar(planes_a, planes_b, tol) -> np.ndarray:
    """(n_a, n_b) True where fin plane a and fin plane b are one plane (normals
    parallel or opposite to 1e-6, b's point within tol of a's plane)."""
    out = np.zeros((len(planes_a), len(planes_b)), bool)
    for a, (ca, ea) in enumerate(planes_a):
        for b, (cb, eb) in enumerate(planes_b):
            out[a, b] = abs(abs(float(ea @ eb)) - 1.0) < 1e-6 and abs(float((cb - ca) @ ea)) < tol
    return out


def _partners(planes, tol) -> np.ndarray:
    """(n_fins, n_fins): each fin and, with THIN_WING, its coplanar partners."""
    own = np.eye(len(planes), dtype=bool)
    return own | _coplanar(planes, planes, tol) if THIN_WING else own


def _paired(panels: PanelSet, planes, tol) -> np.ndarray:
    """(n_fins,) True where a fin has a coplanar partner in the full model (with
    THIN_WING only): another fin of the model in its plane or, in a half model
    (``panels.symmetric``), a mirror twin of one (x, -y, z), which is where a half
    model's partners are (no fin lies in its mirror plane, so two fins of one plane are
    never both in the half)."""
    if not THIN_WING:
        return np.zeros(len(planes), dtype=bool)
    paired = np.any(_coplanar(planes, planes, tol) & ~np.eye(len(planes), dtype=bool), axis=1)
    if panels.symmetric:
        flip = np.array([1.0, -1.0, 1.0])
        paired |= np.any(_coplanar(planes, [(c * flip, e * flip) for c, e in planes], tol), axis=1)
    return paired


def _receiver_sides(planes, x0, tol, partner, cen_r, nrm_r, fin_r, paired) -> np.ndarray:
    """The side of each fin's plane (n_fins, n_r) that receivers (centroids
    ``cen_r``, normals ``nrm_r``, ``fin_r`` the fin they are a panel of or -1) are
    on, as :func:`_fin_sides`: a face (|n . e_t| > 0.5) of fin g with partner[k, g]
    (the fin itself or a coplanar one) the side it faces; a panel of no fin at or
    aft of fin k's leading x, in its half of the cross-section or, if fin k has a
    coplanar partner in the full model (``paired[k]``, :func:`_paired`), anywhere (the
    plane through both fins and the axis splits the body, e.g. a wing on a body), the
    side of the plane it is on (0 within tol of the plane); everything else 0.  For
    mirror images of receivers (:func:`_mirror_sides`) partner[k, g] means g's twin.
    ``paired`` is the full model's in both cases: a half model's fin has its partner
    among the twins, and before session 17 the receivers of the half model itself
    took it from ``partner`` (none there), so the body in the half of the cross-section
    away from the fin was not split by the wing's plane as in the full model
    (tests/unit/test_panair_mirror.py with THIN_WING, Mach 1.3: half / full 1e-3 ...
    6e-3 apart, to rounding with it)."""
    recv = np.zeros((len(planes), len(cen_r)))
    body = fin_r < 0
    g = np.maximum(fin_r, 0)
    for k, (c0, e_t) in enumerate(planes):
        face = nrm_r @ e_t
        sided = ~body & partner[k, g] & (np.abs(face) > 0.5)
        radial = c0 * np.array([0.0, 1.0, 1.0])
        radial /= max(float(np.linalg.norm(radial)), 1e-300)
        half = (cen_r @ radial > tol) | (paired[k] & (cen_r @ radial < -tol))
        near = body & half & (cen_r[:, 0] >= x0[k])
        dist = (cen_r - c0) @ e_t
        across = np.where(np.abs(dist) > tol, np.sign(dist), 0.0)
        recv[k] = np.where(sided, np.sign(face), np.where(near, across, 0.0))
    return recv


def _mirror_sides(panels: PanelSet, keep, cen, nrm, fin_r, cen_r=None, nrm_r=None) -> np.ndarray:
    """For a half model (``panels.symmetric``): the sides (n_fins, n_r), as
    :func:`_receiver_sides`, of the mirror images (x, -y, z) of the receivers
    (default the kept panels; ``fin_r`` their fins, -1 none): the half model adds
    each source's value at the receiver's mirror image (the source's twin acting on
    the receiver), which a fin separates as it would in the full model.  The mirror
    image of fin g's face is a face of g's twin: sided where that twin is fin k's
    partner in the full model (:func:`_partners`: with THIN_WING a coplanar fin,
    without it fin k itself, which no twin is: a half model has no fin in its mirror
    plane, :func:`panair.mesh.mesh_rocket`).  A body receiver's mirror image is sided
    by the full model's rule, in fin k's half of the cross-section (and, where fin k
    has a coplanar partner, the other half too).

    Without these sides (before session 12 the default solver had none, THIN_WING
    none in fin k's own half) a twin fin's far face acted through that fin on the
    body panels of its half of the cross-section that lie in the half model (near
    the mirror plane), which the full model does not allow: CN-alpha half / full
    Basic Finner Mach 1.293 16.67 / 17.21 /rad, 1.6 12.97 / 13.17 (PANAIR 13.05),
    Kestrel Mach 1.3 -5.2 %.  With them the two agree to rounding (5e-13) given the
    same surface-gradient stencil; the full mesh has no gradient neighbour across its
    seam (in the mirror plane) where the half model has the mirror image, which leaves
    CN-alpha 2e-4 .. 1e-3 apart (tests/unit/test_panair_mirror.py)."""
    lifting = ~panels.wake_at_base
    fins = np.unique(panels.network[panels.wake_upper[lifting]])
    planes, x0, tol = _fin_planes(panels, keep, cen, fins)
    flip = np.array([1.0, -1.0, 1.0])
    # without THIN_WING a fin's only partner is itself, which no twin is (no fin in the mirror plane)
    partner = (_coplanar(planes, [(c * flip, e * flip) for c, e in planes], tol) if THIN_WING
               else np.zeros((len(planes), len(planes)), dtype=bool))
    cen_r = cen if cen_r is None else cen_r
    nrm_r = nrm if nrm_r is None else nrm_r
    return _receiver_sides(planes, x0, tol, partner, cen_r * flip, nrm_r * flip, fin_r,
                           _paired(panels, planes, tol))


def _pointed_tip_closure(panels: PanelSet, keep, fins) -> np.ndarray:
    """Panels closing a pointed fin tip (tip chord 0) sideways: fin panels with a
    collapsed edge (the last spanwise line of the fin mesh is one point,
    :func:`panair.mesh._fin_networks`) whose normal lies within 60 deg of the fin's
    mid-plane (|n . n_fin| < 0.5), i.e. the triangles by which the rounded or
    bevelled edges wrap onto the tip point.  They have the role of a tip cap on a
    fin with a tip chord (:func:`_tip_caps`) and are treated as one: solved, not
    integrated, checked against CAP_CP_MAX.  The fin's side triangles of the last
    strip stay in the forces.  (Measured: ICL APEX's swept pointed fins, the
    surface gradient on these slivers gave Cp down to -4e6 on 0.01 % of the area
    at Mach 1.2-2 and sent each Mach number to local inclination; their
    neighbours across the strip face > 60 deg away and are not in the gradient
    stencil, :func:`panair.solver.pressure.surface_gradient`.)"""
    net = panels.network[keep]
    out = np.zeros(len(net), bool)
    if not len(fins):
        return out
    c = panels.corners[keep]
    size = float(np.ptp(panels.corners.reshape(-1, 3), axis=0).max())
    edge = np.linalg.norm(np.roll(c, -1, axis=1) - c, axis=-1)       # (n, 4)
    collapsed = (edge < 1e-9 * size).any(axis=1)
    _, cen, nrm, _ = panels.geometry(1.0)
    cen, nrm = cen[keep], nrm[keep]
    for f in fins:
        on = net == f
        tip = on & collapsed
        if tip.any():
            n_fin = _fin_plane(cen[on])[1]
            out |= tip & (np.abs(nrm @ n_fin) < 0.5)
    return out


def _stagnation_cp(mach):
    """Isentropic stagnation Cp behind a normal shock (Rayleigh pitot formula,
    NACA Report 1135, 1953, eq. 100) [-]."""
    g = GAMMA
    m2 = mach**2
    p02_p1 = (((g + 1) * m2 / 2) ** (g / (g - 1))
              * ((g + 1) / (2 * g * m2 - (g - 1))) ** (1 / (g - 1)))
    return (p02_p1 - 1) / (0.5 * g * m2)


def _sonic_leading_edge(panels: PanelSet, keep, fins, mach) -> np.ndarray:
    """Fin panels at a leading edge that is sonic for linear theory (bool, kept panels).

    A forward-facing fin face (n_x < -sin 1 deg: the leading-edge wedge or bevel)
    whose edge has sweep Lambda and whose face is inclined theta_n in the plane
    normal to the edge sees, by sweep theory (independence principle, R. T. Jones,
    NACA Report 863, 1947), the normal Mach number M_n = M cos Lambda, where
    linear (Ackeret) theory gives it Cp_n = 2 theta_n / sqrt|M_n^2 - 1| on the
    normal dynamic pressure: unbounded as M_n -> 1, the sonic-edge singularity of
    linear theory (e.g. Jones & Cohen, *High Speed Wing Theory*, 1960).  The edge
    is flagged where that value exceeds the largest pressure the real flow can
    have there, the stagnation value at M_n (isentropic below Mach 1, Rayleigh
    pitot above; NACA Report 1135 eq. 44 and 100): linear theory is then outside
    its physical range at that edge because it is near sonic."""
    net = panels.network[keep]
    on = np.isin(net, fins)
    out = np.zeros(len(net), bool)
    if not np.any(on):
        return out
    _, cen, nrm, _ = panels.geometry(1.0)
    cen, nrm = cen[keep], nrm[keep]
    fwd = on & (nrm[:, 0] < -np.sin(np.radians(1.0)))
    idx = np.nonzero(fwd)[0]
    if not len(idx):
        return out
    # the edge is the intersection of the face with the fin's mid-plane (_fin_plane,
    # as _fin_sides): direction n x e_t
    le = np.zeros((len(idx), 3))
    for f in fins:
        of_f = net[idx] == f
        if not np.any(of_f):
            continue
        e_t = _fin_plane(cen[net == f])[1]
        le[of_f] = np.cross(nrm[idx[of_f]], e_t)
    le /= np.maximum(np.linalg.norm(le, axis=1), 1e-300)[:, None]
    cos_sweep = np.sqrt(np.maximum(1.0 - le[:, 0] ** 2, 1e-12))
    theta_n = np.arcsin(np.clip(-nrm[idx, 0] / cos_sweep, 0.0, 1.0))
    mn = mach * cos_sweep
    cp_lin = 2.0 * theta_n / np.sqrt(np.maximum(np.abs(mn * mn - 1.0), 1e-12))
    g = GAMMA
    m = np.maximum(mn, 1e-6)
    cp_pitot = np.where(
        m < 1.0, ((1 + 0.5 * (g - 1) * m**2) ** (g / (g - 1)) - 1) / (0.5 * g * m**2),
        _stagnation_cp(np.maximum(m, 1.0)))
    out[idx] = cp_lin > cp_pitot
    return out


def _divided_difference(phi0, phi1, step):
    """The influence matrix ``(phi1 - phi0) / step[:, None]``, computed in ``phi1``'s memory
    (the caller does not use ``phi1`` again): no two (n, n) temporaries to allocate and
    fault in; the same operations as the expression."""
    A = np.subtract(phi1, phi0, out=phi1)
    A /= step[:, None]
    return A


class SupersonicSolver:
    """Source-panel influence matrix for one supersonic Mach number.

    Parameters
    ----------
    panels : PanelSet
    mach : float [-]
        MACH_SUPERSONIC_MIN <= mach <= MACH_SUPERSONIC_MAX.
    sref : float [m^2]; lref : float [m]; xref : float [m]
    pressure_rule : str
        See :func:`panair.solver.pressure.pressure_coefficient`.
    nose : str
        ``"tangent-cone"`` (default): pressures on forward-facing body
        panels blend from linear theory to the tangent-cone value as
        B tan(the panel's inclination) goes from 0.4 to 0.6
        (:mod:`.nose_correction`); ``"linear"``: linear theory everywhere
        (PANAIR's behaviour).
    mirror : bool
        When the full model is its own mirror image in a plane through the axis
        (:func:`panair.solver.panels.mirror_plane`) the influence rows are computed
        and the system factorised for one panel of each mirror pair
        (:class:`panair.solver.panels.MirrorFold`; the fin sides are mirror-consistent,
        :func:`_fin_sides`), the full system's solution to rounding: in the x-z plane
        for flows without sideslip only, in another plane the flow's symmetric and
        antisymmetric parts as two systems (as :class:`.subsonic.SubsonicSolver`).
    """

    def __init__(self, panels: PanelSet, mach: float, *, sref: float, lref: float,
                 xref: float = 0.0, pressure_rule: str = "second-order",
                 nose: str = "tangent-cone", mirror: bool = False):
        if nose not in ("tangent-cone", "linear"):
            raise InputError(f"nose must be 'tangent-cone' or 'linear', got {nose!r}", field="nose")
        if not MACH_SUPERSONIC_MIN <= mach <= MACH_SUPERSONIC_MAX:
            raise InputError(f"supersonic solver needs {MACH_SUPERSONIC_MIN} <= Mach <= "
                             f"{MACH_SUPERSONIC_MAX}, got {mach}", field="mach")
        self.panels = panels
        self.mach = float(mach)
        self.B = np.sqrt(mach**2 - 1.0)
        self.sref, self.lref, self.xref = float(sref), float(lref), float(xref)
        self.pressure_rule = pressure_rule
        pressure_coefficient(np.zeros((1, 3)), np.array([1.0, 0, 0]), mach, pressure_rule)
        keep = panels.integrate.copy()          # bases are downstream of everything integrated
        self._keep = keep
        idx = -np.ones(panels.n, int)
        idx[keep] = np.arange(keep.sum())
        nb = panels.neighbours[keep]
        self._nb = np.where(nb >= 0, idx[np.maximum(nb, 0)], nb)
        plane = mirror_plane(panels) if mirror else None
        self._fold_twins = idx[plane[0][keep]] if plane is not None else None
        self._fold = MirrorFold(self._fold_twins, plane[1]) if plane is not None else None
        flat, cen, nrm, area = panels.geometry(1.0 / self.B)
        flat, cen, nrm = flat[keep], cen[keep], nrm[keep]
        _, _, g1 = panel_frames(flat, nrm)
        bad = g1 < G1_MIN
        if np.any(bad):
            nets = sorted({panels.names[k] for k in panels.network[keep][bad]})
            raise SolverError(f"Mach {mach}: {bad.sum()} panel(s) of network(s) {nets} are "
                              "superinclined or Mach-inclined (steeper than the Mach cone): "
                              "linear supersonic theory has no solution there; blunt noses, "
                              "blunt (square) fin leading edges and steep shoulders need a "
                              "sharper shape or a lower Mach (or an external PANAIR)")
        self._cen_t, self._nrm_t, self._g1 = cen, nrm, g1
        # regularisation length: the panel's size, but not more than its
        # shortest edge (leading-edge panels are slivers in scaled space)
        edges = np.linalg.norm(np.roll(flat, -1, axis=1) - flat, axis=-1)
        shortest = np.where(edges > 1e-9 * edges.max(), edges, np.inf).min(axis=1)
        scale = np.minimum(np.sqrt(np.maximum(area[keep], 1e-300)), shortest)
        sides = _fin_sides(panels, keep, cen, nrm)
        # a half model adds each source's value at the receiver's mirror image: those
        # pairs are separated by the fin sides of the mirror images (_mirror_sides)
        recv_m = _mirror_sides(panels, keep, cen, nrm, _fin_index(panels, keep)) \
            if panels.symmetric and len(sides[0]) else None
        # fin wakes where the body continues behind a fin (:mod:`.supersonic_wake`):
        # two-faced source sheets, unknowns after the panels' (m of them)
        self._m = m = len(cen)
        lifting = ~panels.wake_at_base
        fins = np.unique(panels.network[panels.wake_upper[lifting]]) if np.any(lifting) else []
        sheets = wake_sheets(panels, keep, fins) if WAKE_SHEETS else None
        self.wake_cells = 0 if sheets is None else sheets.n_cells
        diaphragm = diaphragm_sheets(panels, keep, fins, self.B) if THIN_WING and len(fins) else None
        self.diaphragm_cells = 0 if diaphragm is None else diaphragm.n_cells
        sheets = merge_sheets(sheets, diaphragm)
        tips = None
        if len(fins) and (TIP_DIAPHRAGM if THIN_WING else TIP_DIAPHRAGM_DEFAULT):
            body_like = ~np.isin(panels.network, fins) & keep
            stations = np.unique(np.round(panels.corners[body_like][..., 0].ravel(), 12))
            tips = tip_sheets(panels, keep, fins, self.B, stations)
        self.tip_cells = 0 if tips is None else tips.n_cells
        sheets = merge_sheets(sheets, tips)
        if sheets is not None:
            fl_w, cen_w, nrm_w, scale_w = sheet_geometry(sheets, self.B)
            x_phys = cen[:, 0] * self.B
            self._nb = cut_wake_neighbours(self._nb, np.c_[x_phys, cen[:, 1:]], sides[0],
                                           sheets.x_root_te, sides[1] >= 0)
            self._sheet_twins = None
            if self._fold is not None:
                fold = self._fold
                ext = sheet_twins(self._fold_twins, cen_w, nrm_w,
                                  1e-9 * float(np.ptp(cen, axis=0).max()), reflect=fold._reflect)
                self._fold = MirrorFold(ext, fold.normal) if ext is not None else None
                self._sheet_twins = ext
            flat, cen, nrm = (np.concatenate([a, b]) for a, b in
                              ((flat, fl_w), (cen, cen_w), (nrm, nrm_w)))
            scale = np.concatenate([scale, scale_w])
            # the sheet faces receive from their own fin's side (with THIN_WING also a
            # coplanar partner's), sided as the panels (the same planes, fin_plane's
            # orientation: their own sheets.side to the last bit without THIN_WING)
            planes, x0, tol = _fin_planes(panels, keep, self._cen_t, fins)
            recv_sheet = _receiver_sides(planes, x0, tol, _partners(planes, tol), cen_w, nrm_w,
                                         sheets.fin, _paired(panels, planes, tol))
            sides = sheet_sides(sides, sheets, recv_sheet)
            if recv_m is not None:
                recv_m = np.hstack([recv_m, _mirror_sides(panels, keep, self._cen_t, self._nrm_t,
                                                          sheets.fin, cen_w, nrm_w)])
        if recv_m is not None:
            sides = sides + (recv_m,)
        eps0 = FD_OFFSET * scale
        eps = FD_STEP * scale
        p0 = cen + eps0[:, None] * nrm                      # wetted side, off the panel
        conormal = nrm * np.array([-1.0, 1.0, 1.0])        # mass flux w.n = conormal . grad(phi)
        p1 = p0 + eps[:, None] * conormal
        # both potentials in one pass, the fin-separated pairs skipped; rows aft first,
        # the most likely to meet a Mach-cone singularity (the most panels upstream):
        # a non-finite coefficient makes the whole system unsolvable, found early
        # (folded: the rows of one panel of each mirror pair, the twins' columns added)
        rows = np.arange(len(cen)) if self._fold is None else self._fold.reps
        phi0, phi1, bad_row = source_potential_pair(
            p0, p1, flat, nrm, sides=sides,
            mirror=panels.symmetric, rows=rows[np.argsort(-cen[rows, 0], kind="stable")])
        if bad_row >= 0:
            raise SolverError(f"Mach {mach}: non-finite supersonic influence coefficients")
        if sheets is not None and self._fold is not None and self._fold.odd:
            # another mirror plane: the even and odd systems, each with the wake conditions
            systems = [(f0, A, rows if k == 0 else rows[self._fold.paired]) for k, (f0, A) in
                       enumerate(folded_wake_systems(self._fold, self._sheet_twins, phi0, phi1, eps,
                                                     m, sheets, idx))]
        elif sheets is not None:
            # the wake conditions replace the sheets' rows (wake_rows): one system, folded
            # in the x-z plane
            if self._fold is not None:
                phi0, phi1 = self._fold.fold(phi0[rows]), self._fold.fold(phi1[rows])
            A = _divided_difference(phi0, phi1, eps[rows])
            del phi1
            pos = (lambda j: int(self._fold.rep_of[j])) if self._fold is not None else int
            wake_rows(A, phi0, m, sheets, pos, idx)
            systems = [(phi0, A, rows)]
            phi1 = None
        elif self._fold is None:
            # (potential, influence matrix, rows) of the system, or of the mirror fold's two
            systems = [(phi0, _divided_difference(phi0, phi1, eps[rows]), rows)]
        else:
            fold = self._fold
            systems = [fold.fold_difference(phi0, phi1, rows, eps[rows]) + (rows,)]
            if fold.odd:       # the antisymmetric part's system (mirror plane not x-z)
                systems.append(fold.fold_difference(phi0, phi1, rows, eps[rows], odd=True)
                               + (rows[fold.paired],))
        del phi0, phi1
        self._phi0, self._lu = [], []
        while systems:
            f0, A, r = systems.pop(0)
            self._phi0.append(f0)
            try:
                lu = CausalLU(A, cen[r, 0])
                diag = lu.pivots()
            except SolverError as err:      # no causal factorisation: as singular
                raise SolverError(f"Mach {mach}: singular supersonic influence matrix "
                                  f"(Mach-cone coincidences or duplicated panels; {err})") from err
            del A
            if diag.min() < 1e-8 * diag.max():
                raise SolverError(f"Mach {mach}: singular supersonic influence matrix "
                                  "(Mach-cone coincidences or duplicated panels)")
            self._lu.append(lu)
        _, c_phys, n_phys, a_phys = panels.geometry(1.0)
        self._cen, self._nrm, self._area = c_phys[keep], n_phys[keep], a_phys[keep]
        self._nrm_f = panels.force_normals(n_phys)[keep]   # normals for the force integration
        lifting = ~panels.wake_at_base
        fins = np.unique(panels.network[panels.wake_upper[lifting]]) if np.any(lifting) else []
        closure = _pointed_tip_closure(panels, keep, fins)
        caps = _tip_caps(panels, keep, fins) | closure
        self._caps, self._closure = caps, closure
        #: (n,) bool: the panels whose pressure is in the forces (kept, tip caps left out)
        self.integrated = keep.copy()
        self.integrated[np.flatnonzero(keep)[caps]] = False
        # leading-edge panels where linear theory's pressure is singular (sonic edge):
        # integrable, their load is the theory's leading-edge load (accepted up to
        # CAP_CP_MAX, see solve)
        self._sonic_le = _sonic_leading_edge(panels, keep, fins, self.mach) & ~caps
        self.sonic_le_out_of_range = False
        self.cp_clipped = False
        self._nose = (self._nrm[:, 0] < -np.sin(np.radians(1.0))) \
            & ~np.isin(panels.network[keep], fins) & ~caps
        self._tangent_cone = TangentCone(mach) if nose == "tangent-cone" else None
        # blend linear -> tangent-cone as B tan(delta) goes 0.4 -> 0.6, per panel
        # (linear theory breaks near 0.5: the reference README); our choice
        if np.any(self._nose):
            d_nose = np.arcsin(np.clip(-self._nrm[self._nose, 0], 0, 1))
            if not NOSE_WEIGHT_PER_PANEL:
                d_nose = np.full_like(d_nose, d_nose.max())
            t = np.clip((self.B * np.tan(d_nose) - NOSE_BLEND[0])
                        / (NOSE_BLEND[1] - NOSE_BLEND[0]), 0.0, 1.0)
            self._nose_w = t * t * (3 - 2 * t)
            self.nose_weight = float(self._nose_w.max())
        else:
            self.nose_weight = 0.0
        self._cp_max = 1.5 * _stagnation_cp(mach)
        self._cp_vac = -2.0 / (GAMMA * mach**2)

    def _bad_load(self, cp, sel) -> float:
        """Load of the out-of-range panels relative to the tolerance [-]: the
        largest of |CA|, |CY|, |CN| / tol and of the moments / (tol x arm),
        tol = max(BAD_FORCE_MAX, BAD_FORCE_FRACTION x the largest force
        coefficient of the in-range panels); > 1 means they are not negligible."""
        bad = _bad_panels(cp, self._cp_vac, self._cp_max)
        if not np.any(bad):
            return 0.0
        good = integrate_forces(cp[~bad], self._cen[sel][~bad], self._nrm_f[sel][~bad],
                                self._area[sel][~bad], sref=self.sref, lref=self.lref,
                                xref=self.xref, symmetric=self.panels.symmetric)
        tol = max(BAD_FORCE_MAX, BAD_FORCE_FRACTION * max(abs(good["CA"]), abs(good["CY"]),
                                                          abs(good["CN"])))
        c = integrate_forces(np.where(np.isfinite(cp[bad]), cp[bad], 0.0), self._cen[sel][bad],
                             self._nrm_f[sel][bad], self._area[sel][bad], sref=self.sref,
                             lref=self.lref, xref=self.xref, symmetric=self.panels.symmetric)
        arm = max(float(np.abs(self._cen[:, 0] - self.xref).max()) / self.lref, 1.0)
        force = max(abs(c["CA"]), abs(c["CY"]), abs(c["CN"])) / tol
        moment = max(abs(c["Cl"]), abs(c["Cm"]), abs(c["Cn"])) / (tol * arm)
        return float(max(force, moment))

    def solve(self, alpha, beta=0.0) -> list[PanelResult]:
        """Solve for one or more flow angles (see SubsonicSolver.solve).

        Raises
        ------
        SolverError
            A non-physical surface pressure (the case is reported, not returned).
        """
        alpha, beta = np.broadcast_arrays(np.atleast_1d(np.asarray(alpha, float)),
                                          np.atleast_1d(np.asarray(beta, float)))
        fold = self._fold
        _refuse_sideslip(beta, self.panels.symmetric or (fold is not None and not fold.odd))
        v = np.array([_free_stream(a, b) for a, b in zip(alpha, beta)])
        stretch = np.array([self.B, 1.0, 1.0])
        vt = v / stretch
        rhs = -(self._nrm_t @ vt.T)                      # wetted-side mass flux to impose
        # wake sheets' unknowns follow the panels' (m), their right-hand side 0
        n_all = len(self._phi0[0]) if fold is None else len(fold.rep_of)

        def pad(r):
            return r if n_all == self._m else np.vstack([r, np.zeros((n_all - self._m, r.shape[1]))])
        if fold is None:
            phi = self._phi0[0] @ self._lu[0].solve(pad(rhs))
        elif not fold.odd:
            phi = fold.expand(self._phi0[0] @ self._lu[0].solve(pad(rhs)[fold.reps]))
        else:   # the free stream's parts symmetric and antisymmetric in the mirror plane
            even, odd = (pad(-(self._nrm_t @ (part / stretch).T)) for part in fold.parts(v))
            phi = (fold.expand(self._phi0[0] @ self._lu[0].solve(even[fold.reps]))
                   + fold.expand_odd(self._phi0[1] @ self._lu[1].solve(odd[fold.reps][fold.paired])))
        phi = phi[:self._m]
        nu = self._nrm_t * np.array([-1.0, 1.0, 1.0])
        out = []
        # fin tip caps are solved (the two sides of a fin communicate through them)
        # but not integrated: linear theory puts corner singularities on them (as
        # PANAIR, reference README item 4) while their true load is small (measured
        # on the Basic Finner: <= 0.9 % of CN-alpha, <= 1.4 % of Cm-alpha, signs
        # changing with Mach)
        sel = ~self._caps
        for k in range(len(alpha)):
            g_t = surface_gradient(phi[:, k], self._cen_t, self._nrm_t, self._nb)
            gn = (rhs[:, k] - np.einsum("nj,nj->n", nu, g_t)) / self._g1
            grad = g_t + gn[:, None] * self._nrm_t
            u = grad / np.array([self.B, 1.0, 1.0])
            cp = pressure_coefficient(u, v[k], self.mach, self.pressure_rule)
            if self._tangent_cone is not None and self.nose_weight > 0:
                inc = np.arcsin(np.clip(-(self._nrm[self._nose] @ v[k]), -1.0, 1.0))
                w = self._nose_w
                cp[self._nose] = (1 - w) * cp[self._nose] + w * self._tangent_cone.cp(inc)
            cap_cp = cp[self._caps & ~self._closure]
            # a pointed tip's closure slivers have a degenerate gradient stencil (their
            # Cp is not informative): a Mach-cone coincidence there shows in the potential
            phi_k = phi[:, k]
            closure_phi = np.abs(phi_k[self._closure])
            if closure_phi.size and not closure_phi.max() <= CLOSURE_PHI_RATIO * np.abs(
                    phi_k[~self._closure]).max():
                raise SolverError(
                    f"Mach {self.mach}, alpha {np.degrees(alpha[k]):.2f} deg: singular potential "
                    "on a pointed fin tip (a Mach-cone coincidence); change the Mach number "
                    "slightly or the mesh")
            if np.any(~np.isfinite(cap_cp) | (np.abs(cap_cp) > CAP_CP_MAX)):
                raise SolverError(
                    f"Mach {self.mach}, alpha {np.degrees(alpha[k]):.2f} deg: singular pressure on "
                    f"a fin tip cap (|Cp| up to {np.nanmax(np.abs(cap_cp)):.3g} > {CAP_CP_MAX:g}: "
                    "a Mach-cone coincidence); change the Mach number slightly or the mesh")
            # a sonic leading edge (_sonic_leading_edge): linear theory's compression
            # there is singular (2 theta_n / sqrt|M_n^2 - 1|) but integrable, and the
            # integrated load is the theory's answer (the lift of flat wings is
            # continuous through the sonic-edge condition, e.g. CL_alpha = 4/B at m = 1
            # from both sides for the delta wing, Jones & Cohen 1960): such panels above
            # the stagnation bound stay in the forces and out of the out-of-range count
            # while finite and below CAP_CP_MAX (a Mach-cone coincidence gives ~1e8);
            # expansion past vacuum stays linear theory's large-angle breakdown
            le_cp = cp[self._sonic_le]
            if np.any(~np.isfinite(le_cp) | (np.abs(le_cp) > CAP_CP_MAX)):
                raise SolverError(
                    f"Mach {self.mach}, alpha {np.degrees(alpha[k]):.2f} deg: singular pressure "
                    f"at a sonic fin leading edge (|Cp| up to {np.nanmax(np.abs(le_cp)):.3g})")
            exempt = self._sonic_le & (cp > self._cp_max)
            if np.any(exempt):
                self.sonic_le_out_of_range = True
            sel_chk = sel & ~exempt
            cpi = cp[sel_chk]
            frac = _bad_area(cpi, self._area[sel_chk], self._cp_vac, self._cp_max)
            c = integrate_forces(cp[sel], self._cen[sel], self._nrm_f[sel], self._area[sel],
                                 sref=self.sref, lref=self.lref, xref=self.xref,
                                 symmetric=self.panels.symmetric)
            bad_load = self._bad_load(cpi, sel_chk)
            local = frac <= CLIP_AREA_MAX and bad_load <= CLIP_LOAD_MAX
            if not np.all(np.isfinite(cpi)) or frac > BAD_AREA_MAX or (bad_load > 1.0 and not local):
                raise SolverError(
                    f"Mach {self.mach}, alpha {np.degrees(alpha[k]):.2f} deg: non-physical "
                    f"surface pressure on {100 * frac:.3g} % of the wetted area (Cp "
                    f"{np.nanmin(cpi):.3g} .. {np.nanmax(cpi):.3g}; vacuum {self._cp_vac:.3g}, "
                    f"stagnation {self._cp_max / 1.5:.3g}), carrying {bad_load:.3g} x the "
                    f"tolerated load (force coefficient {BAD_FORCE_MAX} or "
                    f"{100 * BAD_FORCE_FRACTION:g} % of the in-range panels' force)")
            if bad_load > 1.0:
                # a local singularity carrying more than the tolerance (CLIP_AREA_MAX):
                # its panels' pressure bounded by the physical limits
                clip = np.zeros(len(cp), bool)
                clip[sel_chk] = _bad_panels(cpi, self._cp_vac, self._cp_max)
                cp = np.where(clip, np.clip(cp, self._cp_vac, self._cp_max), cp)
                c = integrate_forces(cp[sel], self._cen[sel], self._nrm_f[sel], self._area[sel],
                                     sref=self.sref, lref=self.lref, xref=self.xref,
                                     symmetric=self.panels.symmetric)
                self.cp_clipped = True
            full_cp = np.full(self.panels.n, np.nan)
            full_cp[self._keep] = cp
            full_mu = np.full(self.panels.n, np.nan)
            full_mu[self._keep] = phi[:, k]
            out.append(PanelResult(self.mach, float(alpha[k]), float(beta[k]), cp=full_cp,
                                   mu=full_mu, **c))
        return out
