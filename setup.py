"""The one build step pyproject.toml does not declare stably (setuptools calls its
``ext-modules`` table experimental): the C kernels behind pollard_pin/kinematics/kernels.py
and pollard_pin/painting/spray/kernel.py, compiled at install so that nothing compiles or
caches at run time (read-only installs work). Needs a C compiler and Python's headers. FMA
contraction off: every platform rounds alike."""
from setuptools import Extension, setup

CSRC = "csrc"  # outside the package: compiled into it, not shipped as files
FLAGS = ["-O3", "-ffp-contract=off"]
KERNELS = ("module", "checks", "linalg", "tree", "sense", "rk4")
DEPOSIT = ("deposit", "checks")

setup(ext_modules=[Extension("pollard_pin.kinematics._kernels",
                             sources=[f"{CSRC}/{f}.c" for f in KERNELS],
                             depends=[f"{CSRC}/kernels.h", f"{CSRC}/checks.h"],
                             extra_compile_args=FLAGS),
                   Extension("pollard_pin.painting.spray._deposit",
                             sources=[f"{CSRC}/{f}.c" for f in DEPOSIT],
                             depends=[f"{CSRC}/checks.h"], extra_compile_args=FLAGS)])
