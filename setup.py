# The Python package sap_broadphase (python/sap_broadphase) for catkin_python_setup(): the
# workspace's package then holds it beside the generated sap_broadphase.msg and .srv. Not for
# pip: the compiled module is built by CMake (cmake/python.cmake).
from setuptools import setup

from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["sap_broadphase"], package_dir={"": "python"}))
