"""Debian tools some tests need (chromium, Xvfb), installed by the test set-up when missing."""

import fcntl
import os
import shutil
import subprocess

import pytest


def ensure(binary: str, package: str) -> str:
    """The path of ``binary``, installing Debian's ``package`` with apt-get if it is missing; the test is
    skipped, saying why, where it cannot be installed (not root, no apt-get, no network)."""
    path = shutil.which(binary)
    failure = "needs root and apt-get"
    if path is None and shutil.which("apt-get") and os.geteuid() == 0:
        # one installer at a time: parallel test workers would otherwise meet dpkg's lock and skip
        with open("/tmp/shintai-apt.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            path = shutil.which(binary)  # another worker may have installed it meanwhile
            if path is None:
                env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
                subprocess.run(["apt-get", "update", "-qq"], capture_output=True, timeout=600, env=env)
                done = subprocess.run(["apt-get", "install", "-y", "-qq", package], capture_output=True, text=True,
                                      timeout=900, env=env)
                path = shutil.which(binary)
                failure = (done.stderr.strip().splitlines() or [f"apt-get exit {done.returncode}"])[-1]
    if path is None:
        pytest.skip(f"{binary} is missing and Debian's {package} could not be installed here ({failure})")
    return path
