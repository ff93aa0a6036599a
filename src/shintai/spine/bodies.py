"""Quasi-static spine body: the equilibrium of muscles, discs, gravity and loads (seed 003 §4.3–4.5).

Each posture of the thesis's static experiments is "held several seconds" (§4.7.2); what a spine
does there is the equilibrium −J_mᵀT + τ_disc + τ_grav + τ_ext = 0 (eq. 4.22 plus the forces of
§4.5.2's list). :class:`QuasiStaticSpine` finds it by minimising the potential energy from the
previous equilibrium, every step: a damped Newton (Levenberg–Marquardt) descent on the analytic
gradient within the joint limits (:meth:`QuasiStaticSpine.solve`) — a local minimiser on purpose,
so the spine keeps the posture it settles in, as a physical one does.

Muscle laws (each the derivative of a convex potential of the muscle length λ, so the energy
stays convex in λ; ``k`` is the wire + sensor series stiffness):

* L  — length control, ideal: T = k · max(0, λ − l_r) (the motor holds the wire's end).
* T  — tension control, ideal: T = T_r while the muscle is taut.
* S  — software spring: T = k_e · max(0, λ − l_0), k_e = k_s k / (k_s + k) (eq. 4.36 in series),
  with k_s in N/m: the small-tension limit of the MuJoCo body's default spring on the sensor's ADC
  count (:class:`~shintai.spine.control.CountSpring`, §4.5.2), which hardens through the saturating
  sensor curve. No scenario uses S on this body; the linear law keeps the energy quadratic.
* LL — length control with limit: the L tension, capped at T_l (the motor yields, §4.6.4).

Discs: a linear :class:`~shintai.spine.robots.DiscSpec` (rotational springs on θ), or Rabbit's
:class:`~shintai.spine.robots.RingDiscSpec`, for which every joint also gets an axial gap g_i
(a state) and the disc is a ring of compression-only nonlinear springs between the two faces —
so pulling all muscles compresses the discs and stiffens the joints (§3.5.3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.core.geometry import cross3
from shintai.core.runtime import SET, Body, SimulationDiverged, Snapshot, declare
from shintai.spine.control import Mode
from shintai.spine.geometry import MuscleSet, SpineModel
from shintai.spine.robots import STANDARD_GRAVITY, DiscSpec, RingDiscSpec, SpineRobot


def ring_springs(model: SpineModel, disc: RingDiscSpec) -> MuscleSet:
    """The ring disc as 2-point 'muscles': n_ring points on the lower face of each joint (link i−1,
    half the design gap below the ball centre) paired with points on the upper face (link i, half
    the gap above it). Their lengths are the local face distances d = gap + g at θ = 0."""
    names, paths = [], []
    for i in range(model.n):
        below = model.chain.offsets[i, 2] - disc.gap_m / 2
        for k in range(disc.n_ring):
            a = 2 * np.pi * k / disc.n_ring
            x, y = disc.ring_radius_m * np.cos(a), disc.ring_radius_m * np.sin(a)
            names.append(f"disc{i + 1}:{k}")
            paths.append([(i, (x, y, below)), (i + 1, (x, y, disc.gap_m / 2))])
    return MuscleSet.from_paths(names, paths)


@dataclass
class Equilibrium:
    """A solved static state: posture θ (3n,), gaps g (n,) (zero without ring discs), muscle
    lengths λ and tensions T (m,), and the solver's energy and success flag."""

    theta: np.ndarray
    gap: np.ndarray
    lengths: np.ndarray
    tension: np.ndarray
    energy: float
    success: bool


class QuasiStaticSpine(Body):
    """A spine in static equilibrium at every step (see the module docstring).

    Command channels: ``length`` (m,) commanded muscle lengths λ_r for L and LL muscles (the
    model's eq. 4.25 lengths, not encoder values); ``push`` (3,) an external force [N] on the top
    link at ``push_point`` (its frame), in the base frame; a channel not written keeps its last
    value. Muscle laws, target tensions, springs and limits are set with :meth:`set_laws`. Snapshot:
    ``theta``, ``gap``, ``lengths``, ``tension``, ``top`` (3,) the top link's origin, ``solved``
    (1 if the last equilibrium converged, else 0), ``t``.
    """

    channels = {**declare("length", kind=SET), **declare("push")}  # one length set-point; pushes add
    dt_default = 0.1  # s per equilibrium: a static posture "held for a while"
    max_iterations = 200
    max_step = 0.02  # rad (or m for a gap) per Newton step
    tolerance = 1e-9  # on the energy gradient [N m, N]

    def __init__(self, robot: SpineRobot, loads=None, dt: float = dt_default, gravity: bool = True,
                 push_point=(0.0, 0.0, 0.0)):
        self.robot = robot
        self.model = robot.model
        self.dt = dt
        self.t = 0.0
        self.loads = tuple(robot.loads if loads is None else loads)
        self.gravity = STANDARD_GRAVITY if gravity else 0.0
        self.push_point = np.asarray(push_point, dtype=float)
        self.ring = robot.disc if isinstance(robot.disc, RingDiscSpec) else None
        self.rings = SpineModel(self.model.chain, ring_springs(self.model, self.ring)) if self.ring else None
        n = self.model.n
        self.k_wire = robot.sensor.wire_stiffness_n_m
        self.length_cmd = self.model.lengths(np.zeros(3 * n))
        self.push = np.zeros(3)
        self.set_laws(Mode.L)
        self.state = np.zeros(4 * n if self.ring else 3 * n)
        self.result: Equilibrium | None = None
        self._masses = self._mass_points()
        self.step()

    # -- configuration ----------------------------------------------------------------------------

    def set_laws(self, modes, tension=0.0, k_s=0.0, limit=np.inf) -> None:
        """Per-muscle law (:class:`~shintai.spine.control.Mode`), T-mode tension [N], software
        spring k_s [N/m] and LL limit T_l [N] (scalars or (m,) arrays)."""
        m = self.model.m
        self.modes = np.broadcast_to(np.asarray(modes, dtype=int), (m,)).copy()
        self.tension_cmd = np.broadcast_to(np.asarray(tension, dtype=float), (m,)).copy()
        k_s = np.broadcast_to(np.asarray(k_s, dtype=float), (m,))
        self.k_spring = np.where(k_s > 0, k_s * self.k_wire / np.maximum(k_s + self.k_wire, 1e-12), 0.0)
        self.limit = np.broadcast_to(np.asarray(limit, dtype=float), (m,)).copy()

    def _mass_points(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(link, point, mass) of every mass: vertebrae at mid-segment, and the loads."""
        chain = self.model.chain
        links, points, masses = [], [], []
        for i in range(1, chain.n + 1):
            h = chain.offsets[i, 2] if i < chain.n else 0.0
            links.append(i)
            points.append((0.0, 0.0, h / 2))
            masses.append(self.robot.link_mass_kg[i])
        for load in self.loads:
            links.append(load.link)
            points.append(load.com_m)
            masses.append(load.mass_kg)
        return np.array(links), np.array(points, dtype=float), np.array(masses)

    # -- energy -----------------------------------------------------------------------------------

    def _split(self, x) -> tuple[np.ndarray, np.ndarray | None]:
        n3 = 3 * self.model.n
        return x[:n3], (x[n3:] if self.ring else None)

    def muscle_tension(self, lengths) -> np.ndarray:
        """Tension of each muscle's law at lengths λ (see the module docstring)."""
        stretch = lengths - self.length_cmd
        length_law = self.k_wire * np.maximum(stretch, 0.0)
        T = np.select([self.modes == Mode.L, self.modes == Mode.T, self.modes == Mode.S],
                      [length_law, self.tension_cmd, self.k_spring * np.maximum(stretch, 0.0)],
                      default=np.minimum(length_law, self.limit))
        return T

    def _muscle_energy(self, lengths) -> float:
        stretch = lengths - self.length_cmd
        taut = np.maximum(stretch, 0.0)
        quad = 0.5 * self.k_wire * taut**2
        limit = np.where(np.isfinite(self.limit), self.limit, 0.0)
        cap = limit / self.k_wire  # LL: quadratic up to T_l, then linear with slope T_l
        capped = np.where((taut <= cap) | ~np.isfinite(self.limit), quad, 0.5 * limit * cap + limit * (taut - cap))
        e = np.select([self.modes == Mode.L, self.modes == Mode.T, self.modes == Mode.S],
                      [quad, self.tension_cmd * lengths, 0.5 * self.k_spring * taut**2], default=capped)
        return float(e.sum())

    def _energy(self, x) -> tuple[float, np.ndarray]:
        theta, gap = self._split(x)
        lengths, J, J_gap = self.model.derivatives(theta, gap)
        T = self.muscle_tension(lengths)
        energy = self._muscle_energy(lengths)
        grad_theta = J.T @ T
        grad_gap = J_gap.T @ T if self.ring else None
        e_disc, g_disc_theta, g_disc_gap = self._disc(theta, gap)
        e_ext, g_ext_theta, g_ext_gap = self._external(theta, gap)
        energy += e_disc + e_ext
        grad_theta = grad_theta + g_disc_theta + g_ext_theta
        grad = grad_theta if gap is None else np.concatenate([grad_theta, grad_gap + g_disc_gap + g_ext_gap])
        return energy, grad

    def _disc(self, theta, gap):
        disc = self.robot.disc
        if isinstance(disc, DiscSpec):
            k = np.tile([disc.k_bend_nm_rad, disc.k_bend_nm_rad, disc.k_twist_nm_rad], self.model.n)
            return 0.5 * float(np.sum(k * theta**2)), k * theta, None
        ring = self.ring
        d, J, J_gap = self.rings.derivatives(theta, gap)
        c = ring.compression(d)
        force = ring.force(c)
        energy = float(np.sum(ring.energy(c)))
        g_theta = -J.T @ force
        g_gap = -J_gap.T @ force
        twist = ring.k_twist_nm_rad * theta[2::3]
        energy += 0.5 * float(np.sum(twist * theta[2::3]))
        g_theta[2::3] += twist
        seat = np.minimum(gap + ring.ball_clearance_m, 0.0)  # the ball seats: gap ≥ −clearance
        energy += 0.5 * ring.k_ball_n_m * float(np.sum(seat**2))
        g_gap = g_gap + ring.k_ball_n_m * seat
        return energy, g_theta, g_gap

    def _external(self, theta, gap):
        """Gravity on every mass and the push on the top link, as −Σ F·x with analytic gradient."""
        chain = self.model.chain
        links, points, masses = self._masses
        forces = np.zeros((len(links) + 1, 3))
        forces[:-1, 2] = -masses * self.gravity
        forces[-1] = self.push
        all_links = np.append(links, chain.n)
        all_points = np.vstack([points, self.push_point])
        R, p, Q = chain.frames(theta, gap)
        x = np.einsum("kab,kb->ka", R[all_links], all_points) + p[all_links]
        energy = -float(np.sum(forces * x))
        axes = chain.joint_axes(theta, Q)
        centres = np.repeat(p[1:], 3, axis=0)
        joint_of = np.repeat(np.arange(1, chain.n + 1), 3)
        above = joint_of[None, :] <= all_links[:, None]
        dx = cross3(axes[None, :, :], x[:, None, :] - centres[None, :, :]) * above[..., None]
        g_theta = -np.einsum("ka,kja->j", forces, dx)
        g_gap = None
        if gap is not None:
            gap_dirs = R[:-1, :, 2]
            above_gap = np.arange(1, chain.n + 1)[None, :] <= all_links[:, None]
            g_gap = -np.einsum("ka,ia,ki->i", forces, gap_dirs, above_gap)
        return energy, g_theta, g_gap

    # -- Body interface ---------------------------------------------------------------------------

    def solve(self) -> Equilibrium:
        """The equilibrium nearest the current state: damped Newton on the energy (Hessian by
        differences of the analytic gradient, Levenberg–Marquardt damping, steps bounded by
        ``max_step`` and the joint limits). A global minimiser would let an inverted spine fall
        to its joint limits whenever that lowers the energy; a local one keeps the posture the
        physical spine settles in — and still falls when no equilibrium is nearby."""
        x = self.state.copy()
        lower, upper = self._bounds()
        energy, grad = self._energy(x)
        mu = 1e-6
        for _ in range(self.max_iterations):
            H = self._hessian(x, grad)
            scale = np.maximum(np.abs(np.diag(H)), 1e-9)
            step = -np.linalg.solve(H + mu * np.diag(scale) + 1e-12 * np.eye(x.size), grad)
            step *= min(1.0, self.max_step / max(np.abs(step).max(), 1e-300))
            trial = np.clip(x + step, lower, upper)
            e_trial, g_trial = self._energy(trial)
            if e_trial <= energy:
                x, energy, grad, mu = trial, e_trial, g_trial, max(mu / 4, 1e-9)
                free = ~(((x <= lower) & (grad > 0)) | ((x >= upper) & (grad < 0)))
                if np.abs(grad[free]).max(initial=0.0) < self.tolerance:
                    break
            else:
                mu *= 8
                if mu > 1e12:
                    break
        if not np.all(np.isfinite(x)):
            raise SimulationDiverged(f"quasi-static solve failed at t={self.t:.3f} s")
        free = ~(((x <= lower) & (grad > 0)) | ((x >= upper) & (grad < 0)))
        self.state = x
        theta, gap = self._split(x)
        gap = np.zeros(self.model.n) if gap is None else gap
        lengths = self.model.lengths(theta, gap)
        return Equilibrium(theta, gap, lengths, self.muscle_tension(lengths), energy,
                           bool(np.abs(grad[free]).max(initial=0.0) < self.tolerance))

    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        chain = self.model.chain
        lower, upper = chain.lower.copy(), chain.upper.copy()
        if self.ring:
            lower = np.append(lower, np.full(self.model.n, -3 * self.ring.ball_clearance_m))
            upper = np.append(upper, np.full(self.model.n, self.ring.t_free_m))
        return lower, upper

    def _hessian(self, x, grad, h: float = 1e-7) -> np.ndarray:
        H = np.empty((x.size, x.size))
        for i in range(x.size):
            probe = x.copy()
            probe[i] += h
            H[:, i] = (self._energy(probe)[1] - grad) / h
        return 0.5 * (H + H.T)

    def snapshot(self) -> Snapshot:
        r = self.result
        _, p, _ = self.model.chain.frames(r.theta, r.gap)
        return {"t": self.t, "theta": r.theta.copy(), "gap": r.gap.copy(), "lengths": r.lengths.copy(),
                "tension": r.tension.copy(), "top": p[-1].copy(), "solved": float(r.success)}

    def apply(self, command) -> None:
        if "length" in command:
            self.length_cmd = np.broadcast_to(np.asarray(command["length"], dtype=float), (self.model.m,)).copy()
        if "push" in command:
            self.push = np.asarray(command["push"], dtype=float).reshape(3).copy()

    def step(self) -> None:
        self.result = self.solve()
        self.t += self.dt

