# The results layer's boundary (cmake -P): no source under app/ or ui/ reads
# or writes a file itself -- streams, stdio, Qt's file writers, core's file,
# CSV and JSON readers and writers -- but through core/results (results
# files), core's mesh and image IO, or the few files listed below that own a
# file of their own kind (not a results file):
#   ui/session/project_file.cc  the project (.hiproj) file
#   ui/session/demo_cache.cc    the demo cache's stamp
#   ui/report/report.cc         the report's HTML, PDF and figures
#   app/cli/cmd_export.cc       export's output file name checks
#   app/cli/args.cc             number parsing only (base/csv.h)
#   app/cli/cmd_simulate.cc     number parsing only (base/csv.h)
#   -DSOURCE_DIR=<repository>  [-DEXTRA=<file;...>: checked too, for the test that the check fails]
cmake_policy(VERSION 3.22)
set(owners ui/session/project_file.cc ui/session/demo_cache.cc ui/report/report.cc app/cli/cmd_export.cc
           app/cli/args.cc app/cli/cmd_simulate.cc)
set(patterns
    "std::(o|i)?fstream" "[^a-zA-Z_:]fopen *\\(" "QSaveFile" "QIODevice::(WriteOnly|ReadWrite|Append)"
    "QFile::(WriteOnly|ReadWrite|Append)" "QTextStream" "QDataStream" "QJsonDocument"
    "ReadFileToString" "WriteFileAtomic" "CsvReader" "CsvWriter" "JsonReader" "Json::Parse"
    "#include \"base/(json|csv|file_io)\\.h\"")
file(GLOB_RECURSE files RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/app/*.cc" "${SOURCE_DIR}/app/*.h"
     "${SOURCE_DIR}/ui/*.cc" "${SOURCE_DIR}/ui/*.h")
set(problems "")
foreach(file IN LISTS files EXTRA)
  list(FIND owners "${file}" owner)
  if(NOT owner EQUAL -1)
    continue()
  endif()
  if(IS_ABSOLUTE "${file}")
    set(path "${file}")
  else()
    set(path "${SOURCE_DIR}/${file}")
  endif()
  file(STRINGS "${path}" lines)
  set(n 0)
  foreach(line IN LISTS lines)
    math(EXPR n "${n} + 1")
    if(line MATCHES "^ *//")
      continue()
    endif()
    foreach(p IN LISTS patterns)
      if(line MATCHES "${p}")
        list(APPEND problems "${file}:${n}: ${CMAKE_MATCH_0}")
        break()
      endif()
    endforeach()
  endforeach()
endforeach()
if(problems)
  string(REPLACE ";" "\n  " text "${problems}")
  message(FATAL_ERROR "files read or written outside core/results (read and write them there):\n  ${text}")
endif()
message(STATUS "app/ and ui/ read and write no file themselves")
