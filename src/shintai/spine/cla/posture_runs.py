"""``spine.posture-database``'s run: one posture-database session on the MuJoCo Cla (seed 003 §5.9) and its
metrics, computed from what the session logged (:mod:`shintai.spine.posture_session`,
:mod:`shintai.spine.posture_person`).

The session (chosen; the thesis shows Kenta being taught in photographs, Fig. 5.30, with no protocol): a
strong push forward → taught by hand to a bent-forward posture; two weak pushes; a strong push sideways →
taught a twisted side bend; two weak pushes; the history replayed; then a model motion A → B executed by the
nearest nodes (Fig. 5.29's "動作生成への利用").
"""

from __future__ import annotations

import numpy as np

from shintai.scenarios.experiment import Rig
from shintai.spine.cla.constants import MOTION_A_DEG, MOTION_B_DEG, MOTION_STEPS, TEACH_FORWARD_DEG, TEACH_SIDE_DEG
from shintai.spine.cla.teach_runs import teaching_body
from shintai.spine.control import SETPOINTS, encoder_targets
from shintai.spine.geometry import uniform_posture
from shintai.spine.posture_database import PostureDatabase
from shintai.spine.posture_person import Action, Experimenter
from shintai.spine.posture_session import LIMP, MOVE, PLAY, Supervisor
from shintai.spine.robots import CLA, EXEC_DWELL_S, SAMPLE_PERIOD_S, SETTLE_S
from shintai.spine.tactile import STRONG, WEAK, TriggerLevels


def session_actions(weak_n: float, strong_n: float, execute: bool = True, size: str = "full") -> list[Action]:
    """The session (module doc): pushes on the shoulder block (x forward, y left) [N]. ``size`` "short": one
    strong and one weak push, then the replay (and the execution); "tiny": one weak push and the replay."""
    acts = [
        Action("push", (strong_n, 0.0, 0.0), teach_deg=TEACH_FORWARD_DEG, expect=STRONG),
        Action("push", (0.0, weak_n, 0.0), expect=WEAK),
        Action("push", (-weak_n, 0.0, 0.0), expect=WEAK),
        Action("push", (0.0, strong_n, 0.0), teach_deg=TEACH_SIDE_DEG, expect=STRONG),
        Action("push", (weak_n, 0.0, 0.0), expect=WEAK),
        Action("push", (0.0, -weak_n, 0.0), expect=WEAK),
        Action("replay"),
    ]
    if size == "short":
        acts = [acts[0], acts[1], acts[-1]]
    elif size == "tiny":
        acts = [acts[1], acts[-1]]
    if execute:
        motion = np.linspace(MOTION_A_DEG, MOTION_B_DEG, MOTION_STEPS)
        acts.append(Action("execute", motion_deg=tuple(map(tuple, motion))))
    return acts


def session_rig(actions: list[Action], nn, d_len_mm: float, d_sensor_deg: float | None, levels: TriggerLevels,
                teach_kgf: float, max_s: float = 120.0) -> Rig:
    """Cla (arms down, encoders zeroed, §4.6.4) through ``actions``, until the person is done or ``max_s``; the
    state (:func:`session_result`) holds the database and the log. A pushing hand is an external force on the
    top link (a body hook, every physics step)."""
    body, control = teaching_body(teach_kgf)
    db = PostureDatabase(d_len_mm * 1e-3, None if d_sensor_deg is None else np.radians(d_sensor_deg))
    sup = Supervisor(CLA.model, db, nn, levels, teach_kgf * 9.80665, use_sensor=d_sensor_deg is not None)
    person = Experimenter(actions, sup, CLA.model)
    top = body.id("body", f"link{CLA.n}")

    def push():
        body.data.xfrc_applied[top, :3] = person.force

    body.before_physics.append(push)
    return Rig(body, stages=[[person], [sup], [control]], channels=SETPOINTS, duration=max_s,
               until=lambda snap: person.done, state={"db": db, "log": sup.log, "actions": actions, "person": person,
                                                      "t0": body.t})


def session_result(rig: Rig) -> dict:
    """What a session rig's run left: the database, the log, the actions, the sim time (+ the 1-s zeroing) and
    whether every action finished."""
    s = rig.state
    return {"db": s["db"], "log": s["log"], "sim_time_s": rig.body.t - s["t0"] + 1.0, "actions": s["actions"],
            "finished": s["person"].done}


def _at(log, t: float) -> int:
    return int(np.clip(np.searchsorted(log.t, t), 0, len(log.t) - 1))


def session_metrics(run: dict, levels: TriggerLevels) -> dict[str, float]:
    """Nodes, triggers by level, nudges, history replay and nearest-node execution (module doc)."""
    db, log, actions = run["db"], run["log"], run["actions"]
    m: dict[str, float] = {"nodes_created": len(db.nodes), "finished": int(run["finished"])}
    for tag in ("hold", MOVE, LIMP, PLAY):
        m[f"nodes_created_{tag}"] = sum(n.tag == tag for n in db.nodes)
    m["node_min_separation_mm"] = 1e3 * db.min_separation() if len(db.nodes) > 1 else float("nan")
    m["node_pairs_within_threshold"] = db.violations()
    m["d_len_mm"] = 1e3 * db.d_len
    # triggers: the first one each push caused, against the level it was meant to be
    pushes = [i for i, a in enumerate(actions) if a.kind == "push"]
    first = {}
    for fired, i in log.fired:
        first.setdefault(i, fired)
    for level in (WEAK, STRONG):
        m[f"triggers_{level}"] = sum(f.level == level for f, _ in log.fired)
        m[f"pushes_{level}"] = sum(actions[i].expect == level for i in pushes)
        m[f"triggers_{level}_as_meant"] = sum(actions[i].expect == level and i in first and first[i].level == level
                                              for i in pushes)
    m["pushes_missed"] = sum(i not in first for i in pushes)
    m["weak_axis_as_pushed"] = sum(f.level == WEAK and (f.axis, f.sign) == _pushed_axis(actions[i].force_n)
                                   for i, f in first.items() if i in pushes)
    m["triggers_unprompted"] = sum(i not in pushes for _, i in log.fired)
    m["triggers_extra"] = sum(i in pushes for _, i in log.fired) - sum(i in first for i in pushes)
    push_times = np.array([t for t, _ in log.force]) if log.force else np.zeros(0)
    quiet = [v for t, v in log.tau if push_times.size == 0 or np.min(np.abs(push_times - t)) > 0.5]
    m["hold_tau_max_nm"] = float(max(quiet)) if quiet else float("nan")
    m["push_tau_peak_weak_nm"] = _peak(log, first, actions, WEAK)
    m["push_tau_peak_strong_nm"] = _peak(log, first, actions, STRONG)
    # weak-push nudges: the posture reached after the move and settle against the commanded Θ'
    whole = np.array(log.whole)
    errs = [np.degrees(np.linalg.norm(whole[_at(log, t_end + SETTLE_S - 2 * SAMPLE_PERIOD_S)] - goal))
            for goal, t_end in log.nudges]
    m["nudges"] = len(errs)
    m["nudge_error_deg"] = float(np.mean(errs)) if errs else float("nan")
    m["nudge_mean_deg"] = float(np.mean([f.nudge_deg for f, _ in log.fired if f.level == WEAK])) if errs else 0.0
    m |= _replay_metrics(db, log)
    m |= _execute_metrics(db, log)
    return m


def _pushed_axis(force) -> tuple[int, float]:
    """The whole-spine axis a horizontal push on the shoulders bends about when the spine is straight: x
    (forward) → +pitch, y (left) → −roll."""
    fx, fy = force[0], force[1]
    return (1, float(np.sign(fx))) if abs(fx) >= abs(fy) else (0, float(-np.sign(fy)))


def _peak(log, first, actions, level) -> float:
    peaks = [f.peak_nm for i, f in first.items() if i < len(actions) and actions[i].expect == level]
    return float(np.mean(peaks)) if peaks else float("nan")


def _replay_metrics(db: PostureDatabase, log) -> dict[str, float]:
    """§5.9.2: how closely the replay passes each history node (length, and the posture the node was made in),
    and the time axis: replay interval / teaching interval per history step."""
    play = next((p for p in log.plays if p["kind"] == "replay"), None)
    if play is None:
        return {}
    nodes, arrive = play["nodes"], np.array(play["arrive"])
    enc, whole, t = np.array(log.encoder), np.array(log.whole), np.array(log.t)
    length_err, posture_err = [], []
    for k, node_id in enumerate(nodes):
        lo = arrive[k - 1] if k else play["t0"]
        hi = arrive[k + 1] if k + 1 < len(arrive) else arrive[k] + 1.0
        idx = np.flatnonzero((t >= lo) & (t <= hi))
        if idx.size == 0:
            continue
        node = db.nodes[node_id]
        d = np.linalg.norm(enc[idx] - node.lengths, axis=1)
        j = idx[int(np.argmin(d))]
        length_err.append(1e3 * float(d.min()))
        posture_err.append(float(np.degrees(np.linalg.norm(whole[j] - node.truth))))
    taught_t = np.array(db.history_t[:len(nodes)])
    teach_dt, replay_dt = np.diff(taught_t), np.diff(arrive)
    ratio = replay_dt / np.maximum(teach_dt, 1e-9)
    teaching_s = float(taught_t[-1] - taught_t[0])
    return {"history_length": len(nodes),
            "replay_length_error_mm": float(np.mean(length_err)), "replay_length_error_max_mm": float(max(length_err)),
            "replay_posture_error_deg": float(np.mean(posture_err)),
            "replay_posture_error_max_deg": float(max(posture_err)),
            "teaching_s": teaching_s, "replay_s": float(arrive[-1] - arrive[0]),
            "direct_teaching_samples": int(round(teaching_s / SAMPLE_PERIOD_S)) + 1,
            "time_scale_cv": float(np.std(ratio) / np.mean(ratio)) if ratio.size > 1 else float("nan")}


def _execute_metrics(db: PostureDatabase, log) -> dict[str, float]:
    """§5.9.1: the model motion's nearest nodes, the posture reached at each (after its dwell) against the node's
    own posture, and how far each model posture was from the node standing for it."""
    play = next((p for p in log.plays if p["kind"] == "execute"), None)
    if play is None:
        return {}
    whole = np.array(log.whole)
    nodes, arrive = play["nodes"][1::2], play["arrive"][1::2]
    reached = [np.degrees(np.linalg.norm(whole[_at(log, t - SAMPLE_PERIOD_S)] - db.nodes[k].truth))
               for k, t in zip(nodes, arrive)]
    motion = play["motion"]  # each model posture against the node the plan put for it (nearest in length)
    zero = CLA.model.lengths(np.zeros(3 * CLA.n))
    chosen = [db.nearest(encoder_targets(CLA.model.lengths(uniform_posture(pose, CLA.n)), zero)) for pose in motion]
    gap = [np.degrees(np.linalg.norm(node.truth - pose)) for node, pose in zip(chosen, motion)]
    return {"exec_nodes": len(nodes), "exec_node_error_deg": float(np.mean(reached)),
            "exec_model_gap_deg": float(np.mean(gap)), "exec_dwell_s": EXEC_DWELL_S}
