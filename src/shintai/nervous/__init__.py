"""nervous — the middle layer between programs and robot bodies (seed 003 ch. 6, App. C).

:mod:`~shintai.nervous.hal` (the four calls of §6.3.1, ``sim`` and ``dummy``), :mod:`~shintai.nervous.robot`
(descriptions generated from the model, §6.3.2), :mod:`~shintai.nervous.protocol` and
:mod:`~shintai.nervous.commands` (the line rules of C.2.1), :mod:`~shintai.nervous.nerve` (the plugin loop,
§6.3.4), :mod:`~shintai.nervous.server` (the socket server, §6.3.3), :mod:`~shintai.nervous.plugins`,
:mod:`~shintai.nervous.client` (``NerveClient``), :mod:`~shintai.nervous.plots` (the experiments' figures).
The protocol with a session: ``README.md`` here.
"""
