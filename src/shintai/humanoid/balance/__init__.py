"""HRP2 standing and balancing (seed 000 §5.2, §6.2), shared by the units:

* :mod:`~shintai.humanoid.balance.preview` — the ZMP plan and the LIP preview control of the CoM ([55], §5.2.1).
* :mod:`~shintai.humanoid.balance.stabilizer` — LIP tracking, ZMP distributor and force difference control (§5.2.2).
* :mod:`~shintai.humanoid.balance.stabilizer_tick` — the stabilizer's per-tick arithmetic (foot wrenches, LIP tracking) compiled.
* :mod:`~shintai.humanoid.balance.foot_damping` — foot torque damping, Eqs. 5.1–5.3, with D on a channel.
* :mod:`~shintai.humanoid.balance.foot_attitude` — foot frames, sole forces and the measured ZMP.
* :mod:`~shintai.humanoid.balance.attitude` — the chest IMU's attitude estimate (hrpsys's StateEstimator stand-in), an option of the CoM reading.
* :mod:`~shintai.humanoid.balance.standing` — the stack in its stages and slots (:class:`Standing`), footsteps, the leg IK.
* :mod:`~shintai.humanoid.balance.scooter` — standing on a two-wheeled scooter: lift, sensors, foot pitch (ch. 6, §7.3.3).
"""
