"""The one build step pyproject.toml does not declare stably (setuptools calls its
``ext-modules`` table experimental): the C kernels behind pollard_pin/kinematics/kernels.py,
compiled at install so that nothing compiles or caches at run time (read-only installs work).
Needs a C compiler and Python's headers. FMA contraction off: every platform rounds alike."""
from setuptools import Extension, setup

setup(ext_modules=[Extension("pollard_pin.kinematics._kernels",
                             sources=["pollard_pin/kinematics/_kernels.c"],
                             extra_compile_args=["-O3", "-ffp-contract=off"])])
