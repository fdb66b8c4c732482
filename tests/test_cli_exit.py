"""The ``gearkit`` program ends its process itself once the command is done (``end_process``).

Each case runs a fresh interpreter that reads its command line from ``sys.argv`` as the program
does and then, after ``main()``, prints a line that only an ordinary return reaches: the process
must end with the command's own exit status and complete output, its exit functions run, and
fall back to the ordinary exit where the teardown still has work (a thread that runs on, a tracer).
"""
import os
import subprocess
import sys

import pytest

AFTER = "returned from main"

PROGRAM = """
import atexit, sys, threading
setup = sys.argv[1]
sys.argv = ["gearkit"] + sys.argv[2:]
atexit.register(lambda: print("exit function ran", flush=True))
if setup == "thread":
    done = threading.Event()
    threading.Thread(target=done.wait, args=(60,)).start()  # runs on until main has returned
elif setup == "tracer":
    sys.settrace(lambda *a: None)
from gearkit.cli import main
code = main()
print("%s", code)
if setup == "thread":
    done.set()
sys.exit(code)
""" % AFTER


def run(setup, *argv):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [os.getcwd(), os.environ.get("PYTHONPATH")]))}
    return subprocess.run([sys.executable, "-c", PROGRAM, setup, *argv], capture_output=True, text=True, env=env,
                          timeout=120)


@pytest.mark.parametrize("argv, code", [
    (["gear", "-z", "12", "-m", "2"], 0),
    (["gear", "-z", "2", "-m", "2"], 2),  # bad input: the full parser's error, exit 2
    (["check", "--z1", "6", "--z2", "40", "-m", "2"], 1),  # a design check fails: exit 1
])
def test_the_program_ends_with_its_status_its_output_and_its_exit_functions(argv, code):
    res = run("plain", *argv)
    assert res.returncode == code, res.stderr
    assert AFTER not in res.stdout
    assert res.stdout.rstrip().endswith("exit function ran")
    assert "Traceback" not in res.stderr
    if code == 0:
        assert "tip diameter d_a            28.000000 mm" in res.stdout  # 2 m (z / 2 + 1), the table printed whole


@pytest.mark.parametrize("setup", ["thread", "tracer"])
def test_the_ordinary_exit_where_the_teardown_has_work(setup):
    res = run(setup, "gear", "-z", "12", "-m", "2")
    assert res.returncode == 0, res.stderr
    assert f"{AFTER} 0" in res.stdout
    assert res.stdout.rstrip().endswith("exit function ran")


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full (a device that is always full)")
@pytest.mark.parametrize("unbuffered", ["1", ""])
def test_an_output_that_cannot_be_written_is_reported_as_before(unbuffered):
    """Written at once (unbuffered), the command reports it; buffered, the failed flush at the end is
    left to the ordinary exit, which reports it as always (exit 120)."""
    env = {**os.environ, "PYTHONUNBUFFERED": unbuffered,
           "PYTHONPATH": os.pathsep.join(filter(None, [os.getcwd(), os.environ.get("PYTHONPATH")]))}
    with open("/dev/full", "w") as full:
        res = subprocess.run([sys.executable, "-m", "gearkit", "gear", "-z", "12", "-m", "2"], stdout=full,
                             stderr=subprocess.PIPE, text=True, env=env, timeout=120)
    assert res.returncode == (2 if unbuffered else 120), res.stderr
    assert "No space left on device" in res.stderr


FAULTS = """
import resource, sys
from gearkit.cli import keep_freed_memory
print(keep_freed_memory())
import numpy as np

def faults():
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt

a = np.ones(1 << 18)  # 2 MiB, every page touched, then freed (numpy asks for huge pages from 4 MiB on)
del a
before = faults()
b = np.ones(1 << 18)  # the same again
print(faults() - before)
"""
PAGES = (1 << 21) // 4096  # the pages of 2 MiB (4 KiB pages)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's allocator and Linux page counts")
def test_a_fresh_process_reuses_the_memory_it_freed():
    """The second 2 MiB array lands on the first one's pages (few faults) where the allocator keeps
    freed memory; by default it is mapped afresh, each of its pages faulted in."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [os.getcwd(), os.environ.get("PYTHONPATH")]))
    kept = subprocess.run([sys.executable, "-c", FAULTS], capture_output=True, text=True, env=env, timeout=120)
    assert kept.returncode == 0, kept.stderr
    was_set, faults = kept.stdout.split()
    if was_set != "True":
        pytest.skip("not glibc: no mallopt to set")
    assert int(faults) < PAGES // 10
    plain = FAULTS.replace("print(keep_freed_memory())", "print(True)")
    default = subprocess.run([sys.executable, "-c", plain], capture_output=True, text=True, env=env, timeout=120)
    assert int(default.stdout.split()[1]) > PAGES * 0.9


def test_a_users_own_allocator_setting_wins(monkeypatch):
    from gearkit.cli import keep_freed_memory

    monkeypatch.setenv("MALLOC_TRIM_THRESHOLD_", "131072")
    assert keep_freed_memory() is False
