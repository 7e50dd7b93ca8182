# The assignment kit (student/, docs/student.md): a student's structures compiled into the
# worker (app/worker: the program the judge, accelviz-cli check, talks to) and into the
# viewer. ACCEL_STUDENT_DIR names the folders (a ;-list, relative to the source tree or
# absolute) whose .cpp files are compiled; each registers itself with
# ACCELVIZ_STUDENT_STRUCTURE at program start, so nothing in the core depends on them:
# changing the folder recompiles the student's files and relinks, never the core.
set(ACCEL_STUDENT_DIR "" CACHE STRING
    "Folders of student structures (student/accelviz_student.h) built into the worker and the viewer")

# accel_student_library(TARGET DIR... [DEFINES d...]): an OBJECT library of every .cpp in
# the DIRs (an object library: its objects are linked whole, so the registrations stay).
# Its include path is student/ alone: a student's file that includes a core header does not
# compile, and the core's symbols are not there to link against in the worker.
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
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/student)
  target_link_libraries(${target} PRIVATE accel_warnings)
  target_compile_definitions(${target} PRIVATE ${ARG_DEFINES})
endfunction()

# accelviz_student: what the worker and the viewer link (empty without a folder).
if(ACCEL_STUDENT_DIR)
  accel_student_library(accelviz_student DIRS ${ACCEL_STUDENT_DIR})
  list(LENGTH ACCEL_STUDENT_DIR _accel_student_count)
  message(STATUS "student structures from: ${ACCEL_STUDENT_DIR}")
else()
  add_library(accelviz_student INTERFACE)
endif()
