"""Constants shared by the flight model's numeric and fused paths."""

G0 = 9.80665  # [m/s^2] standard gravity, only for first guesses (the coast horizon)
#: rail-exit residual accepted [m]: the numeric secant, the fused ascent and the
#: symbolic rootfinder stop at the same distance along the rail
RAIL_TOL_M = 1e-10
