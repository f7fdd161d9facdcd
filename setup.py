"""Builds the compiled module plateball._plateball for `pip install .` (metadata: pyproject.toml).

CMake configures this source tree into build/pip-<python tag>/ for the interpreter running pip, with
libplateball linked statically into the extension (no separate shared library to find at import
time) and without the tools, tests and benchmarks; the built extension and the generated
_build_info.py are then copied into the wheel."""
import os
import pathlib
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    """build_ext that runs CMake's plateball_python target instead of compiling sources itself."""

    def build_extension(self, ext):
        build_dir = ROOT / "build" / f"pip-{sys.implementation.cache_tag}"
        configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython_EXECUTABLE={sys.executable}", "-DBUILD_SHARED_LIBS=OFF",
                     "-DCMAKE_POSITION_INDEPENDENT_CODE=ON", "-DPLATEBALL_BUILD_PYTHON=ON",
                     "-DPLATEBALL_BUILD_TESTS=OFF", "-DPLATEBALL_BUILD_BENCHMARKS=OFF",
                     "-DPLATEBALL_BUILD_TOOLS=OFF"]
        # Extra configure arguments, e.g. CI's -DPLATEBALL_WERROR=ON: with the same flags as build/
        # every object is a compiler-cache hit.
        configure += shlex.split(os.environ.get("PLATEBALL_CMAKE_ARGS", ""))
        if shutil.which("ccache"):
            configure += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "plateball_python",
                        "-j", str(os.cpu_count() or 1)], check=True)
        built = build_dir / "python" / "plateball"
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built / ("_plateball" + sysconfig.get_config_var("EXT_SUFFIX")), target)
        shutil.copyfile(built / "_build_info.py", target.parent / "_build_info.py")


setup(ext_modules=[Extension("plateball._plateball", sources=[])], cmdclass={"build_ext": CMakeBuild})
