"""``servo`` — the servo parameters of the body (App. C.3.6 ``servoplugin.c``, "サーボモータに関するプラグイン";
§3.6.2: the on-body software servo lets "制御方式の変更 (PID 制御など)・制御パラメータ (ゲインなど) の動的変更").

Methods: ``show``; ``set KEY VALUE [DOF…]`` (a gain for the given DOF names or indices, all if none) — for
position servos ``kp``, ``kv``; for Cla's muscles the Table 4.6 parameters (``K_Pl``, ``K_Il``, ``K_Dl``,
``K_Pt``, ``K_Dt``, ``T_t``, ``T_l``, ``k_s``, ``T_r`` in SI units); ``mode L|LL|T|S [DOF…]`` (muscles,
§4.6.5; entering L or LL holds the length the muscle has); ``off [DOF…]`` / ``on [DOF…]``. It adds nothing
to the target.
"""

from __future__ import annotations

from shintai.nervous.bodies import ServoError
from shintai.nervous.plugins.base import ADD, CommandError, Plugin
from shintai.nervous.protocol import fmt, number


class Servo(Plugin):
    kind = ADD
    summary = "servo gains, modes, on/off of the body's servos (servoplugin, App. C.3.6)"

    def _apply(self, key: str, value: str, dofs) -> str:
        idx = self.host.dof_indices(dofs)
        try:
            self.host.interface.set_servo(key, value, idx)
        except ServoError as exc:
            raise CommandError(str(exc)) from None
        return self.cmd_show([], None)

    def cmd_show(self, args, call):
        """the servo parameters"""
        return " ".join(f"{k}={fmt(v) if isinstance(v, (int, float)) else v}"
                        for k, v in self.host.interface.servo_state().items())

    def cmd_set(self, args, call):
        """KEY VALUE [DOF…] — a gain (kp, kv; or Table 4.6's for muscles)"""
        if len(args) < 2:
            raise CommandError("set: expected KEY VALUE [DOF…]")
        value = number(args[1], f"set {args[0]}", -1e9, 1e9)
        return self._apply(str(args[0]), str(value), args[2:])

    def cmd_mode(self, args, call):
        """L|LL|T|S [DOF…] — muscle control mode (§4.6)"""
        if not args:
            raise CommandError("mode: expected L|LL|T|S [DOF…]")
        return self._apply("mode", str(args[0]), args[1:])

    def cmd_off(self, args, call):
        """[DOF…] — servo off (limp)"""
        return self._apply("off", "", args)

    def cmd_on(self, args, call):
        """[DOF…] — servo on"""
        return self._apply("on", "", args)
