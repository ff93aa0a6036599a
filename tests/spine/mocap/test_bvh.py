"""The BVH reader and writer, the shipped clip, the retargeting and spine.bvh-retarget's smoke run."""

import json

import numpy as np
import pytest

from shintai.scenarios.registry import ParameterError, get
from shintai.spine.mocap import bvh as bvh
from shintai.spine.mocap import retarget as mocap
from shintai.spine.mocap.constants import TWIST_PEAK_DEG

SMALL = """HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Chest
  {
    OFFSET 0 10 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 10 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.0333333
0 90 0 0 0 0 0 0 30
0 90 0 0 0 0 90 0 0
"""


def test_shipped_clip_frames_channels_and_a_known_angle():
    clip = mocap.load()
    assert clip.n_frames == 91 and clip.frame_time_s == pytest.approx(1 / 30, abs=1e-6)
    assert len(clip.joints) == 20 and clip.n_channels == 6 + 3 * 19
    assert clip.joint("Hips").channels == ("Xposition", "Yposition", "Zposition", "Zrotation", "Xrotation", "Yrotation")
    assert clip.joint("Chest").channels == ("Zrotation", "Xrotation", "Yrotation")  # §5.8.2's example order
    # the wind-up peaks at frame 45 (t = 1.5 s): the chest's share 0.35 of the 55° twist, at rest at frame 0
    assert clip.channel("Chest", "Yrotation")[45] == pytest.approx(0.35 * TWIST_PEAK_DEG, abs=1e-4)
    assert clip.channel("Chest", "Yrotation")[0] == 0.0


def test_shipped_clip_is_what_shintai_writes(tmp_path):
    assert mocap.SHIPPED_CLIP.read_text() == bvh.dumps(mocap.twist_clip())
    again = bvh.read(mocap.regenerate(tmp_path / "again.bvh"))
    assert np.allclose(again.frames, mocap.twist_clip().frames, atol=5e-5)


def test_channel_order_and_forward_kinematics():
    b = bvh.parse(SMALL, "small.bvh")
    R, p = b.world()
    assert np.allclose(p[:, 1], [[0, 100, 0], [0, 100, 0]])
    # frame 0: chest Yrotation 30° turns its x axis towards −z; frame 1: Zrotation 90 then X 0 — Rz(90°)
    assert np.allclose(R[0, 1] @ [1, 0, 0], [np.cos(np.radians(30)), 0, -np.sin(np.radians(30))])
    assert np.allclose(R[1, 1] @ [1, 0, 0], [0, 1, 0], atol=1e-12)


def test_any_channel_layout_is_read():
    six = SMALL.replace("CHANNELS 3 Zrotation Xrotation Yrotation",
                        "CHANNELS 6 Xposition Yposition Zposition Yrotation Xrotation Zrotation")
    six = six.replace("0 90 0 0 0 0 0 0 30", "0 90 0 0 0 0 5 0 0 30 0 0").replace(
        "0 90 0 0 0 0 90 0 0", "0 90 0 0 0 0 5 0 0 0 0 90")
    b = bvh.parse(six, "six.bvh")
    assert b.n_channels == 12 and b.channel("Chest", "Yrotation")[0] == 30
    assert np.allclose(b.world()[1][0, 1], [5, 100, 0])


@pytest.mark.parametrize("broken, where, expected", [
    (lambda s: s.replace("OFFSET 0 10 0\n    CHANNELS", "OFFSET 0 10\n    CHANNELS"), ":8:", "'OFFSET x y z'"),
    (lambda s: s.replace("CHANNELS 3 Z", "CHANNELS 4 Z"), ":9:", "n channel names"),
    (lambda s: s.replace("Xrotation Yrotation\n    End", "Xrotation Wrotation\n    End"), ":9:", "distinct channels"),
    (lambda s: s.replace("0 90 0 0 0 0 90 0 0", "0 90 0 0 0 0 90 0"), ":20:", "9 values in frame 2"),
    (lambda s: s.replace("0 90 0 0 0 0 90 0 0", "0 90 0 0 0 0 90 x 0"), ":20:", "9 numbers in frame 2"),
    (lambda s: s.rsplit("\n", 2)[0] + "\n", ":19:", "frame 2 of 2"),
    (lambda s: s.replace("  }\n}\nMOTION", "  }\nMOTION"), ":15:", "'JOINT name', 'End Site' or '}' in Hips"),
    (lambda s: s.replace("HIERARCHY", "HIERARCHIE"), ":1:", "'HIERARCHY'"),
    (lambda s: s.replace("Frame Time: 0.0333333", "Frame Time: 0"), ":18:", "a positive frame time"),
    (lambda s: s + "1 2 3\n", ":21:", "the end of the file after 2 frames"),
])
def test_a_malformed_file_is_one_clear_line(tmp_path, broken, where, expected):
    path = tmp_path / "bad.bvh"
    path.write_text(broken(SMALL))
    with pytest.raises(bvh.BvhError) as info:
        bvh.read(path)
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"{path}{where}") and expected in message, message


def test_missing_file_is_one_line(tmp_path):
    with pytest.raises(bvh.BvhError, match=r"nope\.bvh: no such file$"):
        bvh.read(tmp_path / "nope.bvh")


@pytest.mark.parametrize("mapping", ["uniform", "by_joint"])
def test_retargeting_keeps_joint_limits(mapping):
    human = mocap.human_trunk(mocap.load())
    stretched = mocap.HumanTrunk(human.times_s, 2 * human.twist_deg,  # a twist far beyond every robot's range
                                 np.einsum("fab,fbc->fac", human.rotation, human.rotation),
                                 np.einsum("fkab,fkbc->fkac", human.segments, human.segments), human.positions)
    for robot in mocap.ROBOTS:
        for trunk in (human, stretched):
            r = mocap.retarget(trunk, robot, mapping)
            assert np.all(r.targets >= r.lower - 1e-12) and np.all(r.targets <= r.upper + 1e-12), robot
    cla = mocap.retarget(stretched, "cla", mapping)
    assert cla.saturated.any() and np.isclose(np.abs(cla.targets).max(), np.radians(18.0))
    assert np.isclose(np.abs(mocap.retarget(stretched, "kenta", mapping).targets).max(), np.radians(10.0))


def test_hrp2_arms_stay_within_table_a2():
    from shintai.humanoid.constants import ARM_JOINTS, joint_range

    arms = mocap.hrp2_arms(mocap.load())
    spec = {j.name: j for j in ARM_JOINTS}
    for name, values in arms.targets.items():
        lo, hi = joint_range(spec[name[2:]], name[0])
        assert np.all(values >= lo - 1e-12) and np.all(values <= hi + 1e-12), name
    # hanging at the start: the arms 15° out (−75° from the T-pose), right roll negative, left positive
    assert np.isclose(np.degrees(arms.targets["r_shoulder_roll"][0]), -15) and np.isclose(
        np.degrees(arms.targets["l_shoulder_roll"][0]), 15)
    assert arms.direction_error_deg[0] < 1e-6 and arms.saturated.any()


def test_spined_robots_twist_and_the_rigid_humanoid_does_not():
    human = mocap.human_trunk(mocap.load())
    assert 50 < human.twist_deg.max() < 56
    for robot in ("cla", "kenta"):
        assert np.max(np.abs(mocap.retarget(human, robot).twist_deg - human.twist_deg)) < 5
    assert np.max(np.abs(mocap.retarget(human, "hrp_rigid").twist_deg)) < 1e-9
    hrp2 = mocap.retarget(human, "hrp2")
    assert np.isclose(hrp2.twist_deg.max(), 45.0) and hrp2.saturated.any()  # the waist yaw stops at 45°
    # §5.8.2's literal DOF matching: Kenta's 3 lowest joints (±10° each) cannot reach 55°
    assert mocap.retarget(human, "kenta", "by_joint").twist_deg.max() < 35


def test_scenario_short_run(smoke):
    run = smoke("spine.bvh-retarget")
    result = run.result
    assert "error" not in result and all(c["ok"] for c in result["checks"])
    m = result["metrics"]
    assert m["twist_tracking_error_cla_deg"] < 5 and m["twist_tracking_error_kenta_deg"] < 5
    assert m["max_twist_hrp_rigid_deg"] == 0 and m["saturation_hrp2_s"] > 0 and m["arm_saturation_hrp2_s"] > 0
    assert (run.out / "twist.png").is_file() and (run.out / "figures.png").is_file()
    assert json.loads((run.out / "metrics.json").read_text())["scenario"] == "spine.bvh-retarget"


def test_scenario_user_file(tmp_path):
    """A user's BVH file is a parameter (its clip read when the parameters are resolved); a file it cannot play
    is a one-line parameter error."""
    user = tmp_path / "mine.bvh"
    user.write_text(mocap.SHIPPED_CLIP.read_text())
    sc = get("spine.bvh-retarget")
    assert sc.resolve({"bvh": str(user)})["bvh"] == str(user) and mocap.load(str(user)).n_frames == 91
    bad = tmp_path / "bad.bvh"
    bad.write_text(SMALL.replace("Frames: 2", "Frames: two"))
    with pytest.raises(ParameterError, match=r"^--set bvh: .*bad\.bvh:17: expected 'Frames: n'"):
        sc.resolve({"bvh": str(bad)})
    with pytest.raises(ParameterError, match="no left shoulder joint"):
        small = tmp_path / "small.bvh"
        small.write_text(SMALL)
        sc.resolve({"bvh": str(small)})
