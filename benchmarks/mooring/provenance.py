"""Where a benchmark number came from: the command, the versions and the machine."""

from __future__ import annotations

import datetime
import importlib.metadata
import os
import platform
import shlex
import sys
from pathlib import Path


def cpu_model() -> str:
    """The CPU model of ``/proc/cpuinfo`` (else ``platform.processor()``)."""
    info = Path("/proc/cpuinfo")
    if info.exists():
        for line in info.read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return platform.processor() or platform.machine()


def cpu() -> str:
    """The CPU model (:func:`cpu_model`) and the core count."""
    return f"{cpu_model()} ({os.cpu_count()} logical cores)"


def machine() -> str:
    """``CPU: ...; load average ...``: the line the comparisons end with."""
    load = os.getloadavg() if hasattr(os, "getloadavg") else None
    tail = f"; load average {load[0]:.1f} (1 min)" if load else ""
    return f"CPU: {cpu()}{tail}"


def version(package: str) -> str | None:
    try:
        return importlib.metadata.version(package)
    except importlib.metadata.PackageNotFoundError:
        return None


def provenance(*packages: str) -> dict[str, object]:
    """The command line, the date, Python, the packages' versions, the CPU and its load (other
    processes on the machine slow the timings)."""
    return {
        "command": " ".join(shlex.quote(a) for a in [Path(sys.executable).name, *sys.argv]),
        "date_utc": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M"),
        "python": platform.python_version(),
        "versions": {p: version(p) for p in packages},
        "cpu": cpu(),
        "platform": platform.platform(),
        "load_average_1_5_15_min": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
    }
