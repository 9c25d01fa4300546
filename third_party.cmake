# Every external package freeturn uses is found here and nowhere else.
# All come from Debian 12 (bookworm) packages; nothing is downloaded or vendored.
# Each find names the apt package that provides it, so a missing one stops
# configuration with the exact `apt-get install` line (scripts/setup.sh installs them).

include_guard(GLOBAL)

function(freeturn_missing what package)
  message(FATAL_ERROR
    "freeturn: ${what} was not found.\n"
    "Install it with:  apt-get install -y ${package}\n"
    "(or run scripts/setup.sh, which installs every missing package).")
endfunction()

# Threads (the C library's) for std::thread -> Threads::Threads
set(THREADS_PREFER_PTHREAD_FLAG ON)
find_package(Threads REQUIRED)

# Eigen 3.4 (header only) -> Eigen3::Eigen
find_package(Eigen3 3.4 QUIET NO_MODULE)
if(NOT TARGET Eigen3::Eigen)
  freeturn_missing("Eigen 3.4" libeigen3-dev)
endif()

# OpenMesh 9 -> OpenMeshCore. Debian's package ships no version file, so no version
# may be requested (see shared/notes/dependencies.md).
find_package(OpenMesh QUIET)
if(NOT TARGET OpenMeshCore)
  freeturn_missing("OpenMesh 9" libopenmesh-dev)
endif()

# yaml-cpp 0.7 -> yaml-cpp (0.8 renames the target yaml-cpp::yaml-cpp)
find_package(yaml-cpp 0.7 QUIET)
if(TARGET yaml-cpp::yaml-cpp)
  set(FREETURN_YAML_TARGET yaml-cpp::yaml-cpp)
elseif(TARGET yaml-cpp)
  set(FREETURN_YAML_TARGET yaml-cpp)
else()
  freeturn_missing("yaml-cpp 0.7" libyaml-cpp-dev)
endif()

# nlohmann-json 3.11 (header only), report.json's writer -> nlohmann_json::nlohmann_json
find_package(nlohmann_json 3.10 QUIET)
if(NOT TARGET nlohmann_json::nlohmann_json)
  freeturn_missing("nlohmann-json 3" nlohmann-json3-dev)
endif()

# pkg-config reads the installed freeturn.pc in the install test.
find_package(PkgConfig QUIET)
if(NOT PKG_CONFIG_FOUND)
  freeturn_missing("pkg-config" pkg-config)
endif()

# doctest 2.4 (header only) -> doctest::doctest, and doctest_discover_tests()
if(FREETURN_BUILD_TESTS)
  find_package(doctest 2.4 QUIET)
  if(NOT TARGET doctest::doctest)
    freeturn_missing("doctest 2.4" doctest-dev)
  endif()
  include(doctest)
endif()

# CLI11 2.1 (header only), the command line's parser -> CLI11::CLI11
find_package(CLI11 2.1 QUIET CONFIG)
if(NOT TARGET CLI11::CLI11)
  freeturn_missing("CLI11 2.1" libcli11-dev)
endif()

# Google Benchmark, only for bench/
if(FREETURN_BUILD_BENCH)
  find_package(benchmark QUIET)
  if(NOT TARGET benchmark::benchmark)
    freeturn_missing("Google Benchmark" libbenchmark-dev)
  endif()
endif()

# The Python module: Python 3.11 headers and pybind11 2.10 (python3-dev, pybind11-dev);
# its tests use NumPy and pytest (python3-numpy, python3-pytest).
if(FREETURN_PYTHON)
  # Debian's Python, whose NumPy and pytest the packages install (not another one on PATH).
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 3.9 QUIET COMPONENTS Interpreter Development.Module)
  if(NOT Python3_Development.Module_FOUND)
    freeturn_missing("the Python 3 headers" python3-dev)
  endif()
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 2.10 QUIET CONFIG)
  if(NOT pybind11_FOUND)
    freeturn_missing("pybind11 2.10" pybind11-dev)
  endif()
endif()
