# The package carries a compiled module (_mtacc*.so, built by CMake): the wheel is tagged for
# this interpreter and platform, not as pure Python.
from setuptools import Distribution, setup


class BinaryDistribution(Distribution):
    def has_ext_modules(self):
        return True


setup(distclass=BinaryDistribution)
