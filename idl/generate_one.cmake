# Runs fastddsgen on one IDL file (cmake -P script, called from idl/CMakeLists.txt).
# fastddsgen regenerates every included IDL flat into its output folder, so we
# generate into a private temp folder and copy only this IDL's four files into
# <OUT_DIR>/<pkg>/msg/, which keeps parallel builds from racing on shared files.
foreach(var FASTDDSGEN IDL_ROOT IDL_FILE OUT_DIR NAME REL_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "generate_one.cmake: ${var} is not set")
  endif()
endforeach()
set(tmp "${OUT_DIR}/.tmp/${REL_DIR}/${NAME}")
file(REMOVE_RECURSE "${tmp}")
file(MAKE_DIRECTORY "${tmp}")
execute_process(
  COMMAND "${FASTDDSGEN}" -cs -typeros2 -replace -d "${tmp}" -I "${IDL_ROOT}" "${IDL_FILE}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${tmp}/${NAME}PubSubTypes.cxx")
  message(FATAL_ERROR "fastddsgen failed on ${IDL_FILE} (exit ${rc}):\n${out}\n${err}")
endif()
file(MAKE_DIRECTORY "${OUT_DIR}/${REL_DIR}")
foreach(suffix .h .cxx PubSubTypes.h PubSubTypes.cxx)
  file(COPY_FILE "${tmp}/${NAME}${suffix}" "${OUT_DIR}/${REL_DIR}/${NAME}${suffix}" ONLY_IF_DIFFERENT)
endforeach()
file(REMOVE_RECURSE "${tmp}")
