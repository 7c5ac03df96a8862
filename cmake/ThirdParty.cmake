# Imported targets for the Debian packages that ship no CMake config file, defined once for every module
# (lib/CMakeLists.txt includes this before adding them):
#   GeographicLib::GeographicLib  libgeographiclib-dev: only FindGeographicLib.cmake, in
#                                 /usr/share/cmake/geographiclib (WGS-84 ↔ ENU, ECEF)
#   Erfa::erfa                    liberfa-dev: the IAU SOFA astrometry routines, header <erfa.h>, no CMake file
if(NOT TARGET GeographicLib::GeographicLib)
  list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
  find_package(GeographicLib REQUIRED)
  add_library(GeographicLib::GeographicLib INTERFACE IMPORTED GLOBAL)
  target_include_directories(GeographicLib::GeographicLib INTERFACE ${GeographicLib_INCLUDE_DIRS})
  target_link_libraries(GeographicLib::GeographicLib INTERFACE ${GeographicLib_LIBRARIES})
endif()
if(NOT TARGET Erfa::erfa)
  find_path(ERFA_INCLUDE_DIR erfa.h REQUIRED)
  find_library(ERFA_LIBRARY erfa REQUIRED)
  add_library(Erfa::erfa INTERFACE IMPORTED GLOBAL)
  target_include_directories(Erfa::erfa INTERFACE ${ERFA_INCLUDE_DIR})
  target_link_libraries(Erfa::erfa INTERFACE ${ERFA_LIBRARY})
endif()
