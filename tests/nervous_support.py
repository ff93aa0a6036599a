"""Helpers shared by the nervous tests (tests/nervous): run lines on a Nerve, run packets."""

from shintai.nervous.commands import Client

THESIS_RC = ["load-plugin seqplugin", "create-plugin sequence sequence", "start sequence"]  # App. C.2.2


def run(nerve, lines, client=None):
    """Execute lines; their reply texts (None for silent lines)."""
    client = client or Client()
    return [nerve.execute(line, client).text for line in lines]


def ticks(nerve, n):
    for _ in range(n):
        nerve.tick()
