"""The machine a report's figures were measured on, in one line (for the tools/*_report.py
generators; standard library only)."""
import os
import platform


def machine():
    """'<cpu model>, <n> cores, <system> <release>'."""
    cpu = "?"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores, {platform.system()} {platform.release()}"
