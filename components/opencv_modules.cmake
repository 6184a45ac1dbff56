# OpenCV's core, imgproc and imgcodecs as the targets opencv_core,
# opencv_imgproc and opencv_imgcodecs, named by OpenCV_LIBS. Debian ships
# OpenCV's CMake package only in libopencv-dev, which installs every module
# and what they need (VTK, MPI, Qt); with libopencv-core-dev,
# libopencv-imgproc-dev and libopencv-imgcodecs-dev alone (what setup.sh
# installs) the headers and libraries are found directly. Included by the
# build and by structlocConfig.cmake.
find_package(OpenCV QUIET COMPONENTS core imgproc imgcodecs)
if(NOT OpenCV_FOUND)
  find_path(structloc_OpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
  set(OpenCV_LIBS opencv_core opencv_imgproc opencv_imgcodecs)
  foreach(module IN LISTS OpenCV_LIBS)
    if(TARGET ${module})
      continue()
    endif()
    find_library(structloc_${module}_LIBRARY ${module})
    if(NOT structloc_OpenCV_INCLUDE_DIR OR NOT structloc_${module}_LIBRARY)
      message(FATAL_ERROR "OpenCV's ${module} was not found: install libopencv-core-dev, "
                          "libopencv-imgproc-dev and libopencv-imgcodecs-dev (Debian)")
    endif()
    add_library(${module} SHARED IMPORTED)
    set_target_properties(${module} PROPERTIES
      IMPORTED_LOCATION "${structloc_${module}_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${structloc_OpenCV_INCLUDE_DIR}")
  endforeach()
  set(OpenCV_FOUND TRUE)
endif()
