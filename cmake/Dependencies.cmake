# Every third-party library comes from a Debian 12 package (scripts/install_deps.sh).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenImageIO 2.4 REQUIRED)
find_package(OpenEXR 3 REQUIRED)
find_package(TBB REQUIRED)
find_package(CLI11 2 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(embree 3.13 REQUIRED)
find_package(TinyGLTF REQUIRED)
find_package(assimp 5.2 REQUIRED)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs videoio calib3d)
find_package(Catch2 2 REQUIRED)
set(Python3_EXECUTABLE /usr/bin/python3)
find_package(Python3 REQUIRED COMPONENTS Interpreter Development)
find_package(pybind11 2.10 REQUIRED)

# Debian's interpreter (with python3-numpy, python3-pytest and python3-torch), whatever python3 is first on PATH.
set(FLOWSCAPE_PYTHON /usr/bin/python3 CACHE FILEPATH "Python interpreter for the plugin and its tests")
