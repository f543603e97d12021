"""Brute-force midpoint quadrature over a bilinear quad (panel-solver tests)."""
import numpy as np


def quad_samples(quad, n):
    """(points (n, n, 3), area weights (n, n)) of the midpoint rule on the
    bilinear surface through the 4 corners ``quad``."""
    g = (np.arange(n) + 0.5) / n
    u, v = np.meshgrid(g, g, indexing="ij")
    q = quad
    pts = ((1 - u)[..., None] * (1 - v)[..., None] * q[0] + (1 - u)[..., None] * v[..., None] * q[1]
           + u[..., None] * v[..., None] * q[2] + u[..., None] * (1 - v)[..., None] * q[3])
    du = (1 - v)[..., None] * (q[3] - q[0]) + v[..., None] * (q[2] - q[1])
    dv = (1 - u)[..., None] * (q[1] - q[0]) + u[..., None] * (q[2] - q[3])
    return pts, np.linalg.norm(np.cross(du, dv), axis=-1) / n**2
