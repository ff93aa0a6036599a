"""The spine robots' MuJoCo models for export (``shintai model``, :mod:`shintai.sim.export`). Rabbit has none:
its ring discs are modelled quasi-statically (:mod:`shintai.spine.bodies`)."""

from shintai.sim.export import model
from shintai.spine.bodies_mujoco import build_spec
from shintai.spine.cla.body import build_spec as build_cla_body
from shintai.spine.cla.crawl import kneeling_spec
from shintai.spine.hanzous.body import build_spec as build_hanzous
from shintai.spine.kenta.body import kenta_spec
from shintai.spine.kenta.constants import SPINE_ARMATURE_KGM2
from shintai.spine.robots import CLA, KENTA
from shintai.spine.sq43.body import build_spec as build_sq43


@model("spine.cla", "Cla's muscle spine: five vertebrae, eight wire muscles on reels, raised arms (seed 003 §3.6)")
def cla():
    return build_spec(CLA)


@model("spine.kenta", "Kenta's spine: ten joints and forty muscles, ligaments included (seed 003 §3.7)")
def kenta():
    spec = build_spec(KENTA)
    for joint in spec.joints:  # kenta_body's armature: the 280 N m/rad discs need it at the 0.5 ms step
        if joint.name.startswith("j") and ":" not in joint.name:
            joint.armature = SPINE_ARMATURE_KGM2
    return spec


@model("spine.sq43", "SQ43: 14-DOF quadruped, shoulder + compliant 3-block spine + hip, 1.9 kg (seed 003 §3.2, §5.6)")
def sq43():
    return build_sq43()


@model("spine.cla-crawl", "Cla on hands and knees for crawling: free pelvis, the five spine joints servoed, arms and legs "
       "on the floor (seed 003 §3.6, §5.2.9)")
def cla_crawl():
    return kneeling_spec()


@model("spine.hanzous", "HanzouS: 18 servoed joints, a cam-set leaf-spring trunk, hanging from bar 0 of three "
       "(seed 003 §3.3, §5.7)")
def hanzous():
    return build_hanzous()


@model("spine.cla-seated", "Whole-body Cla seated on a stool before a desk: the muscle spine (8 wire muscles), "
       "4-DOF arms and legs, pan/tilt neck with the head camera, desk and objects (seed 003 §3.6.2, §5.2)")
def cla_seated():
    return build_cla_body("seated")


@model("spine.cla-standing", "Whole-body Cla standing free on the floor: the muscle spine, 4-DOF arms and legs, neck, "
       "4 FSRs per sole for the centre of pressure (seed 003 §3.6.2, eq. 3.5, §5.2.7)")
def cla_standing():
    return build_cla_body("standing")


@model("spine.cla-lying", "Whole-body Cla for rolling over: the standing Cla with its trunk, head and limbs touching "
       "the floor (placed on its back by spine.cla-roll-over; seed 003 §5.2.8)")
def cla_lying():
    from shintai.spine.cla.roll_over import lying_spec

    return lying_spec()


@model("spine.kenta-body", "Kenta's whole body: the 40-muscle, 10-joint spine with ligaments, arms (chest and shoulder "
       "balls, elbow, wrist), a 5-ball wire-driven neck, a pan/tilt eye linkage with two cameras (seed 003 §3.7)")
def kenta_body():
    return kenta_spec()
