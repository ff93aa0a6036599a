"""Fixtures for nervous: a Nerve on the dummy interface (no sockets), a server on its own thread."""

import pytest
from nervous_support import THESIS_RC, run

from shintai.nervous.nerve import Nerve
from shintai.nervous.server import ServerThread


@pytest.fixture
def nerve():
    """arm3 on the dummy interface, the thesis's .nervousrc lines run: the sequence plugin is running."""
    n = Nerve("arm3", "dummy")
    assert run(n, THESIS_RC) == ["ok sequence (set): " + n.loaded["sequence"].summary, "ok sequence (sequence)",
                                 "ok started sequence"]
    return n


@pytest.fixture
def server():
    """A real-time 1 ms dummy arm3 server on a thread (it sleeps between packets), sequence running."""
    n = Nerve("arm3", "dummy", realtime=True)
    run(n, THESIS_RC)
    with ServerThread(n) as srv:
        yield srv
