"""HanzouS (seed 003 §3.3, §5.7): the brachiating robot with a leaf-spring trunk.

body — HanzouS as a MuJoCo body: 18 servoed joints, the cam-stiffened leaf-spring trunk (§3.3, §5.7.2)
constants — HanzouS's numbers: the bars, the gripper, the brachiation timing and genes (§5.7)
brachiation — 8 key postures spline-interpolated, grasp and release, and the GA over them (§3.3.3, §5.7.3–5.7.5)
plots — the brachiation pictures (Fig. 3.14, Figs. 5.24–5.27)

trained/ — the shipped GA result for ``spine.hanzous-brachiation``.
"""
