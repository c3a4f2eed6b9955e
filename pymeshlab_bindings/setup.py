"""Builds the MeshLab plugin (C++, see ../plugin) and ships it inside the package.

The build links against the installed pymeshlab's libmeshlab-common, so install with
`pip install --no-build-isolation ./pymeshlab_bindings` into an environment that has pymeshlab.
"""
import os
import pathlib
import shutil
import subprocess

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parent


class BuildWithPlugin(build_py):
    def run(self):
        super().run()
        script = REPO / "scripts" / "build_plugin.sh"
        if not script.exists():
            raise RuntimeError(f"{script} not found: install from a checkout of meshlab-acd")
        env = dict(os.environ, ACD_SCALAR="double")
        subprocess.check_call(["bash", str(script)], env=env)
        build_dir = subprocess.check_output(
            ["bash", "-c", f'source "{REPO}/scripts/env.sh" && printf %s "$ACD_BUILD_DIR"'], env=env, text=True)
        built = pathlib.Path(build_dir) / "filter_acd" / "libfilter_acd.so"
        dest = pathlib.Path(self.build_lib) / "pymeshlab_acd" / "lib"
        dest.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, dest / built.name)


class BinaryDistribution(Distribution):
    """The package ships a compiled plugin: its wheel is a platform wheel, not a pure one."""

    def has_ext_modules(self):
        return True


setup(cmdclass={"build_py": BuildWithPlugin}, distclass=BinaryDistribution)
