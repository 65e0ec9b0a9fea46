# For catkin_python_setup() only (cmake/python.cmake): do not run it by hand.
from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=['bearing_sim', 'bearing_sim.campaign'], package_dir={'': 'python'}))
