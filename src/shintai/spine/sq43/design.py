"""SQ43 spine design search: compass ("steepest-descent") search over three vertebra angles (seed 003 §3.2.3).

The thesis stiffens SQ43's memory-foam spine in torsion by reshaping it. Design variables: the
angles a_i of the four rigid vertebra parts A_i with the horizontal plane (Fig. 3.3), |a_i| ≤ 30°,
with parts 1 and 4 at the same height and equal lengths l (eq. 3.1), so a_4 follows from a_1..a_3.
The objective is the height of the lifted left-front foot above the ground after lifting it from
four-leg support (maximised). The search evaluates f at a(t) and at a(t) ± 0.5° eᵢ, moves to the
best, and stops when the current point is best (eq. 3.2); four starts (Table 3.1).

**What replaces the FEM (ours).** The thesis coupled a commercial FEM of the foam spine to a
multibody model; the mesh, the material, L, l and the evaluation instant are not in the text. We use
a quasi-static linear model:

* the spine is the chain A1 B1 A2 B2 A3 B3 A4 of rigid parts A and three foam blocks B, each block a
  6-DOF linear spring in its own frame, whose axis is the bisector of its two neighbours (the block
  is glued to their end faces) — the block is soft in torsion (foam only), stiff in lateral bending
  (the styrene rods of servo A) and in vertical bending (the wires of servo B) (§3.2.2). Inclining a
  block turns part of the body's twist into the block's stiff lateral bending: this is how the a_i
  change the torsional stiffness;
* the 6×6 spine compliance between the shoulder and hip frames is the sum of the block compliances
  carried to the shoulder end (serial chain);
* the robot is two rigid frames (shoulder with the front legs, hip with the hind legs) on rigid legs;
  with the left-front foot lifted the other three feet are pinned, gravity loads the frames, and the
  deformation minimises the elastic plus gravity energy under the pins;
* objective = lift height + the lifted foot's vertical displacement (its sag) [mm].
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import null_space

from shintai.core.geometry import skew
from shintai.spine.robots import SQ43, STANDARD_GRAVITY

TABLE_3_1 = SQ43.starts_deg  # the four starts of Table 3.1 [deg]
STEP_DEG = SQ43.search_step_deg  # δa_i/δt = 0.5°, §3.2.3
BOUND_DEG = SQ43.angle_limit_deg  # |a_i| ≤ 30°, §3.2.3


@dataclass(frozen=True)
class SQ43Params:
    """Model constants. Only the mass (1.9 kg) and the block length (10 mm) are the thesis's."""

    spine_length_m: float = SQ43.spine_length_m  # L, not in the text (chosen in robots.SQ43)
    block_length_m: float = SQ43.foam_length_m  # part B length in y, §3.2.3
    body_width_m: float = 0.10  # distance between left and right feet (chosen)
    leg_offset_m: float = 0.02  # hip/shoulder joints ahead of / behind the spine ends (chosen)
    stance_height_m: float = 0.10  # spine above the ground (chosen)
    lift_m: float = 0.03  # how far the left-front leg raises its foot relative to the shoulder (chosen)
    mass_kg: float = SQ43.mass_kg  # §3.2.2; split equally between the shoulder and hip frames
    # Block stiffness in its own frame (chosen; the foam M-41 is not characterised in the text):
    # translations along the axis / lateral / normal [N/m], rotations torsion / vertical / lateral bending [N·m/rad].
    k_axial: float = 1.0e5
    k_shear: float = 2.0e4
    k_torsion: float = 6.0  # foam only: the soft direction the thesis wanted to stiffen
    k_bend_vertical: float = 30.0  # foam + wires of servo B
    k_bend_lateral: float = 60.0  # foam + styrene rods of servo A


def fourth_angle(a123_deg) -> float:
    """a_4 from eq. (3.1): sin a_1 + … + sin a_4 = 0 (NaN when no real a_4 exists)."""
    s = -np.sum(np.sin(np.radians(a123_deg)))
    return float(np.degrees(np.arcsin(s))) if abs(s) <= 1.0 else float("nan")


def feasible(a123_deg) -> bool:
    """All four |a_i| ≤ 30° (a_4 from eq. 3.1)."""
    a4 = fourth_angle(a123_deg)
    return bool(np.all(np.abs(a123_deg) <= BOUND_DEG + 1e-9) and np.isfinite(a4) and abs(a4) <= BOUND_DEG + 1e-9)


@dataclass(frozen=True)
class SpineShape:
    """Points along the spine (shoulder end first) and the three blocks: centres and axis angles."""

    angles_deg: np.ndarray  # a_1..a_4
    part_length_m: float  # l
    polyline: np.ndarray  # (9, 3): shoulder end, then the ends of A1, B1, A2, …, A4 (= hip end)
    block_centres: np.ndarray  # (3, 3)
    block_angles_rad: np.ndarray  # (3,) bisector of the two neighbouring parts


def spine_shape(a123_deg, prm: SQ43Params = SQ43Params()) -> SpineShape:
    """Geometry from (a_1, a_2, a_3); x right, y forward, z up; a_i > 0 rises towards the rear.

    Eq. (3.1) "must be slightly modified" for the 10-mm blocks B (the modification is not given):
    chosen, the blocks span 10 mm in y and nothing in z, so Σ sin a_i = 0 is unchanged and
    l = (L − 3·10 mm) / Σ cos a_i.
    """
    a = np.radians(np.r_[a123_deg, fourth_angle(a123_deg)])
    l = (prm.spine_length_m - 3 * prm.block_length_m) / np.sum(np.cos(a))
    pts = [np.array([0.0, prm.spine_length_m / 2, 0.0])]
    for i, ai in enumerate(a):
        pts.append(pts[-1] + l * np.array([0.0, -np.cos(ai), np.sin(ai)]))
        if i < 3:
            pts.append(pts[-1] + np.array([0.0, -prm.block_length_m, 0.0]))
    poly = np.array(pts)
    centres = np.array([(poly[2 * k + 1] + poly[2 * k + 2]) / 2 for k in range(3)])
    return SpineShape(np.degrees(a), float(l), poly, centres, (a[:3] + a[1:]) / 2)


def spine_compliance(shape: SpineShape, prm: SQ43Params = SQ43Params()) -> np.ndarray:
    """6×6 compliance of the shoulder end w.r.t. the hip end, at the shoulder end point.

    Wrench (f, m) at the shoulder end → displacement (δp, δθ) there; Σ_k T_kᵀ C_k T_k over the blocks.
    """
    local = np.diag(1.0 / np.array([prm.k_axial, prm.k_shear, prm.k_shear,
                                    prm.k_torsion, prm.k_bend_vertical, prm.k_bend_lateral]))
    end = shape.polyline[0]
    C = np.zeros((6, 6))
    for centre, beta in zip(shape.block_centres, shape.block_angles_rad):
        axis = np.array([0.0, -np.cos(beta), np.sin(beta)])
        lateral = np.array([1.0, 0.0, 0.0])
        R = np.column_stack((axis, lateral, np.cross(axis, lateral)))  # local (axis, lateral, normal)
        Rw = np.kron(np.eye(2), R)
        T = np.block([[np.eye(3), np.zeros((3, 3))], [skew(end - centre), np.eye(3)]])
        C += T.T @ Rw @ local @ Rw.T @ T
    return C


def torsional_stiffness(a123_deg, prm: SQ43Params = SQ43Params()) -> float:
    """Pure twist moment about the body axis y per radian of twist, 1/C_θyθy [N·m/rad] (the thesis's aim)."""
    return float(1.0 / spine_compliance(spine_shape(a123_deg, prm), prm)[4, 4])


@dataclass(frozen=True)
class Stance:
    """Foot positions (LF, RF, LH, RH) and the two frames' reference points and mass centres."""

    feet: dict
    shoulder: np.ndarray
    hip: np.ndarray
    com_shoulder: np.ndarray
    com_hip: np.ndarray


def stance(shape: SpineShape, prm: SQ43Params = SQ43Params()) -> Stance:
    """Four-leg stance from which the left front leg is lifted: feet under the leg joints.

    Chosen: no shift of the centre of mass before the lift (the thesis describes the evaluation as
    lifting the leg "from four-leg support", §3.2.3). The centre of mass then lies on the RF–LH
    diagonal, so RH carries no load and the front frame's weight twists the spine.
    """
    w, y = prm.body_width_m / 2, prm.spine_length_m / 2 + prm.leg_offset_m
    shoulder, hip = shape.polyline[0], shape.polyline[-1]
    feet = {"LF": (-w, y), "RF": (w, y), "LH": (-w, -y), "RH": (w, -y)}
    feet = {k: np.array([x, yy, -prm.stance_height_m]) for k, (x, yy) in feet.items()}
    return Stance(feet, shoulder, hip, shoulder + [0.0, prm.leg_offset_m, 0.0], hip - [0.0, prm.leg_offset_m, 0.0])


def point_rows(point: np.ndarray, origin: np.ndarray) -> np.ndarray:
    """3×6 map from a frame's small motion (δp at ``origin``, δθ) to the motion of ``point``: δp − [r]×δθ."""
    return np.hstack((np.eye(3), -skew(point - origin)))


@dataclass(frozen=True)
class LiftResult:
    height_m: float  # lifted foot above the ground (the objective)
    sag_m: float  # vertical displacement of the lifted foot from the spine's deformation
    twist_rad: float  # shoulder roll about y relative to the hip
    reactions_n: np.ndarray  # vertical contact force at RF, LH, RH


# Contacts: (foot, frame, axes). Vertical support at the three standing feet; the feet slide freely
# (chosen: the contact model of the thesis's multibody simulation is not given; with sliding feet the
# spine alone carries the front frame's weight moment, the torsion the thesis names). The LH (x, y)
# and RH (y) rows only remove the horizontal rigid-body motion; with vertical loads they carry nothing.
CONTACTS = (("RF", 0, (2,)), ("LH", 6, (0, 1, 2)), ("RH", 6, (1, 2)))


def lift_left_front(a123_deg, prm: SQ43Params = SQ43Params()) -> LiftResult:
    """Quasi-static lift of the left front leg on the compliant spine (module doc).

    Unknowns u = (δp_S, δθ_S, δp_H, δθ_H) at the spine ends; minimise ½ uᵀKu + gᵀu subject to the
    contacts (null-space solve); the pin forces follow from Aᵀλ = Ku + g.
    """
    shape = spine_shape(a123_deg, prm)
    st = stance(shape, prm)
    Ks = np.linalg.inv(spine_compliance(shape, prm))
    D = np.hstack((np.eye(6), -np.vstack((point_rows(st.shoulder, st.hip), np.hstack((np.zeros((3, 3)), np.eye(3)))))))
    K = D.T @ Ks @ D  # relative motion of the shoulder end w.r.t. the hip frame
    weight = prm.mass_kg / 2 * STANDARD_GRAVITY
    g = np.zeros(12)
    g[:6] = weight * point_rows(st.com_shoulder, st.shoulder)[2]
    g[6:] = weight * point_rows(st.com_hip, st.hip)[2]
    rows = []
    for name, col, axes in CONTACTS:
        origin = st.shoulder if col == 0 else st.hip
        for axis in axes:
            row = np.zeros(12)
            row[col:col + 6] = point_rows(st.feet[name], origin)[axis]
            rows.append(row)
    A = np.array(rows)
    N = null_space(A)
    u = N @ np.linalg.solve(N.T @ K @ N, -N.T @ g)
    lam = np.linalg.lstsq(A.T, K @ u + g, rcond=None)[0]  # contact forces on the robot
    lifted = st.feet["LF"] + [0.0, 0.0, prm.lift_m]
    sag = float((point_rows(lifted, st.shoulder) @ u[:6])[2])
    return LiftResult(prm.lift_m + sag, sag, float(u[4] - u[10]), lam[[0, 3, 5]])


def lifted_foot_height_mm(a123_deg, prm: SQ43Params = SQ43Params()) -> float:
    """The §3.2.3 evaluation value f(a_1, a_2, a_3): lifted-foot height above the ground [mm]."""
    return 1e3 * lift_left_front(a123_deg, prm).height_m


# ---------------------------------------------------------------------------------------- the search

@dataclass
class SearchPath:
    """One compass search: the visited points, their values, and how many distinct points were evaluated."""

    points: list = field(default_factory=list)  # a(t) [deg]
    values: list = field(default_factory=list)  # f(a(t))
    evaluations: int = 0

    @property
    def end(self) -> np.ndarray:
        return self.points[-1]

    @property
    def best(self) -> float:
        return self.values[-1]


def compass_search(f: Callable[[np.ndarray], float], start, step: float = STEP_DEG, bound: float = BOUND_DEG,
                   is_feasible: Callable[[np.ndarray], bool] | None = None) -> SearchPath:
    """Maximise f by the neighbourhood search of §3.2.3.

    At a(t) evaluate f(a(t)) and f(a(t) ± step·eᵢ); move to the largest; stop when a(t) itself is
    largest (eq. 3.2; a tie keeps a(t), so the search ends). Neighbours outside |aᵢ| ≤ bound or
    failing ``is_feasible`` are not evaluated. Points live on the grid start + k·step exactly
    (integer offsets), so no rounding drift. Each strict improvement visits a new grid point, so the
    search terminates.
    """
    start = np.asarray(start, dtype=float)
    point = lambda k: start + step * np.asarray(k)  # noqa: E731
    ok = lambda a: bool(np.all(np.abs(a) <= bound + 1e-9)) and (is_feasible is None or is_feasible(a))  # noqa: E731
    if not ok(start):
        raise ValueError(f"compass_search: start {start.tolist()} is outside the feasible set")
    cache: dict[tuple, float] = {}

    def value(k: tuple) -> float:
        if k not in cache:
            cache[k] = float(f(point(k)))
        return cache[k]

    k = (0,) * len(start)
    path = SearchPath([start], [value(k)])
    while True:
        neighbours = [tuple(np.add(k, s * e)) for e in np.eye(len(k), dtype=int) for s in (1, -1)]
        neighbours = [n for n in neighbours if ok(point(n))]
        best = max(neighbours, key=value, default=None)
        if best is None or value(best) <= value(k):
            path.evaluations = len(cache)
            return path
        k = best
        path.points.append(point(k))
        path.values.append(value(k))
