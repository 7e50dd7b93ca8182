# The assignment kit (student/, docs/student.md): a student's structures compiled into the
# CLI, the viewer and the tests. ACCEL_STUDENT_DIR names the folders (a ;-list, relative
# to the source tree or absolute) whose .cpp files are compiled; each registers itself
# with ACCELVIZ_STUDENT_STRUCTURE at program start, so nothing in the core depends on them:
# changing the folder recompiles the student's files and relinks, never the core.
set(ACCEL_STUDENT_DIR "" CACHE STRING
    "Folders of student structures (student/accelviz_student.h) built into the CLI, viewer and tests")

# accel_student_library(TARGET DIR... [DEFINES d...]): an OBJECT library of every .cpp in
# the DIRs (an object library: its objects are linked whole, so the registrations stay).
function(accel_student_library target)
  cmake_parse_arguments(ARG "" "" "DIRS;DEFINES" ${ARGN})
  set(sources "")
  foreach(dir IN LISTS ARG_DIRS)
    cmake_path(ABSOLUTE_PATH dir BASE_DIRECTORY "${PROJECT_SOURCE_DIR}" NORMALIZE OUTPUT_VARIABLE abs)
    if(NOT IS_DIRECTORY "${abs}")
      message(FATAL_ERROR "ACCEL_STUDENT_DIR: ${dir}: no such folder")
    endif()
    file(GLOB found CONFIGURE_DEPENDS "${abs}/*.cpp")
    if(NOT found)
      message(FATAL_ERROR "ACCEL_STUDENT_DIR: ${dir}: no .cpp file in it")
    endif()
    list(APPEND sources ${found})
  endforeach()
  add_library(${target} OBJECT ${sources})
  target_link_libraries(${target} PUBLIC accelviz_core PRIVATE accel_warnings)
  target_compile_definitions(${target} PRIVATE ${ARG_DEFINES})
endfunction()

# accelviz_student: what the CLI, the viewer and the tests link (empty without a folder).
if(ACCEL_STUDENT_DIR)
  accel_student_library(accelviz_student DIRS ${ACCEL_STUDENT_DIR})
  list(LENGTH ACCEL_STUDENT_DIR _accel_student_count)
  message(STATUS "student structures from: ${ACCEL_STUDENT_DIR}")
else()
  add_library(accelviz_student INTERFACE)
endif()
