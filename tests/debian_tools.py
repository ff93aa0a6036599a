"""Debian tools some tests need (chromium, Xvfb), installed by the test set-up when missing."""

import os
import shutil
import subprocess

import pytest


def ensure(binary: str, package: str) -> str:
    """The path of ``binary``, installing Debian's ``package`` with apt-get if it is missing; the test is
    skipped, saying why, where it cannot be installed (not root, no apt-get, no network)."""
    path = shutil.which(binary)
    if path is None and shutil.which("apt-get") and os.geteuid() == 0:
        env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
        subprocess.run(["apt-get", "update", "-qq"], capture_output=True, timeout=600, env=env)
        subprocess.run(["apt-get", "install", "-y", "-qq", package], capture_output=True, timeout=900, env=env)
        path = shutil.which(binary)
    if path is None:
        pytest.skip(f"{binary} is missing and Debian's {package} could not be installed here (needs root and apt-get)")
    return path
