# The direction of the source tree (docs/architecture.md): a folder's files may include their own
# folder's headers and those of the folders listed before it, never one listed after it or beside
# it. Run at configure time by CMakeLists.txt and as the test `source_folders_include_downwards`:
#   cmake -DVORODEC_ROOT=<source dir> -P cmake/check_layers.cmake
# Each entry is folder:rank; equal ranks are siblings and may not include each other.
set(VORODEC_LAYERS
    geometry:0 io:1 checkpoint:2 model:3 laws:4 solver:5 loading:5 measure:6 input:7 engine:8
    drivers:9 outputs:9 run:10 workflows:11 cli:12)

function(vorodec_check_layers root)
  set(errors "")
  foreach(entry ${VORODEC_LAYERS})
    string(REPLACE ":" ";" pair ${entry})
    list(GET pair 0 folder)
    list(GET pair 1 rank)
    set(rank_${folder} ${rank})
    list(APPEND folders ${folder})
  endforeach()
  file(GLOB top RELATIVE ${root}/src LIST_DIRECTORIES true ${root}/src/*)
  foreach(dir ${top})
    if(IS_DIRECTORY ${root}/src/${dir} AND NOT DEFINED rank_${dir})
      string(APPEND errors "  src/${dir}/ is not in VORODEC_LAYERS (cmake/check_layers.cmake)\n")
    endif()
  endforeach()
  foreach(folder ${folders})
    file(GLOB_RECURSE sources ${root}/src/${folder}/*.cpp ${root}/src/${folder}/*.hpp
         ${root}/include/vorodec/${folder}/*.hpp)
    foreach(source ${sources})
      file(RELATIVE_PATH rel ${root} ${source})
      file(STRINGS ${source} includes REGEX "^#include \"")
      foreach(line ${includes})
        if(line MATCHES "^#include \"vorodec/([a-z_]+)/")
          set(target ${CMAKE_MATCH_1})
          if(NOT DEFINED rank_${target})
            string(APPEND errors "  ${rel}: ${line}: folder '${target}' has no layer\n")
          elseif(NOT target STREQUAL folder AND NOT rank_${target} LESS rank_${folder})
            string(APPEND errors "  ${rel}: ${line}: ${folder} may not include ${target}\n")
          endif()
        elseif(line MATCHES "^#include \"\\.\\./")
          string(APPEND errors "  ${rel}: ${line}: include another folder's public header\n")
        endif()
      endforeach()
    endforeach()
  endforeach()
  if(errors)
    message(FATAL_ERROR "Source folders include upwards:\n${errors}")
  endif()
endfunction()

if(CMAKE_SCRIPT_MODE_FILE)
  vorodec_check_layers(${VORODEC_ROOT})
endif()
