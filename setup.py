# The Python package sap_broadphase (python/sap_broadphase), two ways:
#
# * pip (pyproject.toml): `pip install --no-build-isolation .` builds the engine and the compiled
#   module _sap_broadphase with CMake (the ROS-free build's target sap_broadphase_python, with
#   the interpreter that runs pip) and installs both as one package. CMAKE_ARGS adds arguments
#   to CMake's configure step (e.g. CMAKE_ARGS=-DSAP_NATIVE=ON).
# * catkin: catkin_python_setup() reads this file (catkin's interrogate_setup_dot_py.py runs it
#   with setup() replaced, not as __main__) and `catkin_make install` runs it with
#   CATKIN_BINARY_DIR set: then only the pure package, which the workspace's package holds
#   beside the generated sap_broadphase.msg and .srv; catkin builds the compiled part itself
#   (cmake/python.cmake).
import os
import pathlib
import shlex
import shutil
import subprocess
import sys
import sysconfig
import xml.etree.ElementTree

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
PACKAGE = dict(packages=["sap_broadphase"], package_dir={"": "python"})
MODULE_TARGET = "sap_broadphase_python"  # cmake/python.cmake


def run_by_catkin():
    return __name__ != "__main__" or "CATKIN_BINARY_DIR" in os.environ


def package_xml(tag):
    return xml.etree.ElementTree.parse(ROOT / "package.xml").getroot().findtext(tag).strip()


def pybind11_hint():
    """pybind11's CMake files where the Python package pybind11 has them (pip's build isolation
    installs it there); Debian's pybind11-dev has them where CMake looks anyway."""
    try:
        import pybind11  # pylint: disable=import-outside-toplevel
    except ImportError:
        return []
    return ["-Dpybind11_DIR=" + pybind11.get_cmake_dir()]


class CMakeBuild(build_ext):
    """Builds the compiled module with the project's CMake build instead of compiling sources."""

    def build_extension(self, ext):
        build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DSAP_BUILD_ROS=OFF",
                     "-DSAP_BUILD_TESTS=OFF", "-DSAP_BUILD_BENCHMARKS=OFF",
                     "-DSAP_BUILD_PYTHON=ON", "-DCMAKE_BUILD_TYPE=Release",
                     "-DPython3_EXECUTABLE=" + sys.executable]
        configure += pybind11_hint() + shlex.split(os.environ.get("CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", MODULE_TARGET, "-j", jobs],
                       check=True)
        built = build_dir / "python" / "sap_broadphase" / (
            "_sap_broadphase" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.is_file():
            raise RuntimeError(f"CMake did not build {built}: is pybind11 installed for "
                               f"{sys.executable} (Debian: pybind11-dev python3-dev)?")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


if run_by_catkin():
    from catkin_pkg.python_setup import generate_distutils_setup

    setup(**generate_distutils_setup(**PACKAGE))
else:
    BUILD = ROOT / "build" / "pip"  # beside the other builds (build/ws, build/no_ros)
    BUILD.mkdir(parents=True, exist_ok=True)
    setup(
        name="sap_broadphase",
        version=package_xml("version"),
        description="Exact parallel Sweep and Prune broad phase for axis-aligned boxes",
        license=package_xml("license"),
        python_requires=">=3.8",
        install_requires=["numpy"],
        ext_modules=[Extension("sap_broadphase._sap_broadphase", sources=[])],
        cmdclass={"build_ext": CMakeBuild},
        options={"build": {"build_base": str(BUILD)}, "egg_info": {"egg_base": str(BUILD)}},
        zip_safe=False,
        **PACKAGE,
    )
