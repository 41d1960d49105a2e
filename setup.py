"""setuptools' side of `pip install --no-build-isolation .`: the package
python/beamslider/ and its compiled part `_core`, which the project's CMake
builds (target beamslider_python) in ./build, the folder README's commands
use, so that after them only the module is linked and copied. Set
BEAMSLIDER_BUILD_DIR to build elsewhere. Nothing is downloaded."""
import os
import subprocess

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, extension):
        build_dir = os.environ.get("BEAMSLIDER_BUILD_DIR", os.path.join(ROOT, "build"))
        # The module is built for Debian's /usr/bin/python3 (the CMake
        # cache's BEAMSLIDER_PYTHON): install it with that Python or a venv
        # made from it.
        subprocess.check_call(["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release"])
        subprocess.check_call(["cmake", "--build", build_dir, "--target", "beamslider_python", "-j",
                               str(os.cpu_count() or 1)])
        built = os.path.join(build_dir, "python", "beamslider")
        name = next(f for f in os.listdir(built) if f.startswith("_core") and f.endswith(".so"))
        target = self.get_ext_fullpath(extension.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        self.copy_file(os.path.join(built, name), target)


# setuptools' own staging goes to build/setuptools, out of CMake's way.
setup(packages=["beamslider"], package_dir={"": "python"},
      ext_modules=[Extension("beamslider._core", sources=[])], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": os.path.join("build", "setuptools")}})
