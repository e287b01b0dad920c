"""Waiting for a child process while measuring its peak resident memory, as the tools'
benchmarks, cross-check and studies report it.

The peak is the child's own VmHWM (/proc/<pid>/status), polled while it runs: wait4's
ru_maxrss is not usable for small programs, because Linux carries the forking Python
process's high-water mark into the child across exec. VmHWM only grows, so the last reading
before the exit is within one polling interval of the true peak.
"""
import os
import time


def vm_hwm(pid):
    """The VmHWM of a running process in bytes (None once it has exited or is unreadable)."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def wait_measured(proc, poll=0.01):
    """Waits for the subprocess.Popen `proc`: (exit code, CPU s, peak bytes). Sets
    proc.returncode."""
    peak = 0
    while True:
        pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            break
        peak = max(peak, vm_hwm(proc.pid) or 0)
        time.sleep(poll)
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, usage.ru_utime + usage.ru_stime, peak
