# Sourced by scripts/run.sh, build.sh and build_web.sh: takes the kit's options out of "$@".
#   --student DIR    a folder of student structures to build in (repeatable; docs/student.md)
#   --no-student     build none (clears what an earlier --student left in the build folder)
# Sets student_cmake_args (the CMake -D to add, if any) and remaining_args (everything else).
student_cmake_args=()
remaining_args=()
_student_dirs=""
_student_given=0
while [ $# -gt 0 ]; do
  case "$1" in
    --student)
      if [ $# -lt 2 ] || [ -z "$2" ]; then
        echo "$(basename "$0"): --student needs a folder of student structures (docs/student.md)" >&2
        exit 2
      fi
      if [ ! -d "$2" ]; then
        echo "$(basename "$0"): --student $2: no such folder" >&2
        exit 2
      fi
      _student_dirs="${_student_dirs:+$_student_dirs;}$(cd "$2" && pwd)"
      _student_given=1
      shift 2 ;;
    --student=*)
      set -- --student "${1#--student=}" "${@:2}" ;;
    --no-student)
      _student_dirs=""
      _student_given=1
      shift ;;
    *)
      remaining_args+=("$1")
      shift ;;
  esac
done
if [ "$_student_given" = 1 ]; then
  student_cmake_args=("-DACCEL_STUDENT_DIR=$_student_dirs")
fi
