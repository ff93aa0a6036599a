"""Motion capture onto spined robots (seed 003 §5.8, Fig. 5.28).

bvh — BVH files: a strict reader, a writer and forward kinematics (§5.8.2)
constants — the shipped clip's numbers and the pictures' tile size (§5.8)
plots — the retargeting's pictures (Fig. 5.28)
retarget — the shipped clip (``twist_clip.bvh``) and its retargeting onto the robots' spines (§5.8)
"""
