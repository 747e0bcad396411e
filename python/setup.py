"""pip builds the plugin's C++ extension (flowscape_native: OpenImageIO image reading, remapping)
where it can: a plugin-only CMake build of the repository around this folder (core, geometry,
stitcher, formats; Eigen, OpenImageIO, OpenCV, TBB, pybind11 from Debian). Without a compiler, CMake or
those libraries, or outside the repository (an sdist), it says why and installs the package as
pure Python, which reads files through its numpy fallback; FLOWSCAPE_REQUIRE_EXTENSION=1 makes
that an error instead, FLOWSCAPE_PURE_PYTHON=1 skips the extension."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

REPOSITORY = Path(__file__).resolve().parent.parent


class CMakeBuild(build_ext):
    def build_extension(self, extension):
        target = Path(self.get_ext_fullpath(extension.name))
        target.unlink(missing_ok=True)  # an earlier build's, in the in-tree build folder
        try:
            built = self.cmake_build()
        except (OSError, subprocess.CalledProcessError) as error:
            if os.environ.get("FLOWSCAPE_REQUIRE_EXTENSION") == "1":
                raise
            print(f"flowscape: the C++ extension was not built ({error}); the plugin reads "
                  "files through its numpy fallback", file=sys.stderr)
            return
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)

    def cmake_build(self):
        if os.environ.get("FLOWSCAPE_PURE_PYTHON") == "1":
            raise OSError("FLOWSCAPE_PURE_PYTHON=1")
        if not (REPOSITORY / "CMakeLists.txt").exists():
            raise OSError(f"{REPOSITORY} is not the FlowScape repository")
        build = Path(self.build_temp).resolve() / "cmake"
        subprocess.run(["cmake", "-S", str(REPOSITORY), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                        "-DFLOWSCAPE_PLUGIN_ONLY=ON", "-DBUILD_TESTING=OFF",
                        f"-DFLOWSCAPE_PYTHON={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "flowscape_native", "-j",
                        str(os.cpu_count() or 1)], check=True)
        built = sorted((build / "python").glob("flowscape_native*.so"))
        if not built:
            raise OSError(f"CMake made no flowscape_native*.so in {build / 'python'}")
        return built[0]


setup(ext_modules=[Extension("flowscape_native", sources=[])], cmdclass={"build_ext": CMakeBuild})
