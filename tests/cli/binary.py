"""The ballast binary under test, for the Python suites ctest runs with the binary's
path as their only argument:

    import binary
    ...
    if __name__ == "__main__":
        binary.main()
"""
import os
import subprocess
import sys
import unittest

PATH = None  # set by main() from the command line


def ballast(*args, timeout=300, **kwargs):
    """Runs `ballast ARGS`, capturing its output as text."""
    return subprocess.run([PATH, *args], capture_output=True, text=True, timeout=timeout,
                          **kwargs)


def succeed(*args, timeout=900, **kwargs):
    """Runs `ballast ARGS` and raises, with its output, unless it exits 0: for a test's
    set-up, where a failed run must say why rather than fail every test after it."""
    r = ballast(*args, timeout=timeout, **kwargs)
    if r.returncode != 0:
        raise RuntimeError(f"ballast {' '.join(args)} exited {r.returncode}:\n"
                           f"{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return r


def main():
    global PATH
    PATH = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
