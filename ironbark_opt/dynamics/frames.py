"""Reference frames and quaternion algebra (symbolic-safe, CasADi).

Frames (documented once, here):

- **L**, the local-level launch frame: origin at the foot of the launch rail
  at the site elevation, flat Earth; axes x east, y north, z up (ENU).
  Position ``r_l`` is the rocket CG in L [m]; altitude above sea level is
  ``r_l[2] + site_elevation``.
- **B**, the body frame: origin at the CG, x forward along the rocket axis
  (toward the nose), y and z completing a right-handed triad; the roll
  orientation of y/z at launch is fixed by :func:`launch_quaternion`.
  Note the axial *position* convention used everywhere else (``x`` aft of the
  nose tip) points the other way: a station ``x_aft`` sits at body
  coordinate ``-x_aft`` relative to the nose tip.
- **Velocity/load-factor plane**: spanned by the body axis and the air-
  relative velocity; the total angle of attack ``alpha`` is measured in it
  and the normal force lies in it (aeroballistic convention,
  Zipfel, *Modeling and Simulation of Aerospace Vehicle Dynamics*, 2nd ed.,
  sec. 9.2).

Attitude is the unit quaternion ``q = (q0, q1, q2, q3)`` (scalar first,
Hamilton convention) rotating B-vectors into L: ``v_l = q * v_b * conj(q)``.
Its kinematics are ``dq/dt = 1/2 q * (0, w_b)`` (Zipfel eq. 4.76) plus a
renormalisation term (see :func:`quaternion_rate`).
"""
from __future__ import annotations

import casadi as ca


def quat_multiply(a, b):
    """Hamilton product ``a * b`` of two quaternions (scalar first)."""
    a0, a1, a2, a3 = a[0], a[1], a[2], a[3]
    b0, b1, b2, b3 = b[0], b[1], b[2], b[3]
    return ca.vertcat(
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


def rotation_matrix(q):
    """Direction-cosine matrix T_LB (B -> L) of the unit quaternion ``q``.

    Zipfel eq. 4.79 transposed (his [T]^BL maps L to B).
    """
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    return ca.vertcat(
        ca.horzcat(q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)),
        ca.horzcat(2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1)),
        ca.horzcat(2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3),
    )


def quaternion_rate(q, w_b, gain: float = 1.0):
    """dq/dt [1/s] for body rates ``w_b`` [rad/s] with norm feedback.

    ``1/2 q * (0, w_b) + gain * (1 - |q|^2) q``: the second term drives the
    norm back to 1 (Zipfel sec. 4.3.3 "quaternion normalisation"), so a fixed
    step integrator does not drift; on the exact solution it is zero.
    """
    dq = 0.5 * quat_multiply(q, ca.vertcat(0, w_b))
    return dq + gain * (1 - ca.dot(q, q)) * q


def launch_quaternion(inclination, heading):
    """Attitude on the rail: body x along the rail.

    Parameters
    ----------
    inclination : float or SX [rad]
        Rail angle above the horizontal.
    heading : float or SX [rad]
        Direction the rail points, clockwise from north.

    The body axis becomes ``(cos i sin h, cos i cos h, sin i)`` in L:
    ``q = q_z(pi/2 - h) * q_y(-i)`` (rotate up by ``i`` about y, then about the
    vertical to the heading).  Symbolic-safe.
    """
    a = 0.5 * (ca.pi / 2 - heading)
    b = -0.5 * inclination
    qz = ca.vertcat(ca.cos(a), 0, 0, ca.sin(a))
    qy = ca.vertcat(ca.cos(b), 0, ca.sin(b), 0)
    return quat_multiply(qz, qy)


def rail_direction_l(inclination, heading):
    """Unit vector along the rail in L [-] (east, north, up)."""
    return ca.vertcat(ca.cos(inclination) * ca.sin(heading),
                      ca.cos(inclination) * ca.cos(heading),
                      ca.sin(inclination))
