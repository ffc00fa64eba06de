# Precompiled headers (VILSLAM_PCH): the standard, Eigen and OpenCV core headers most files include, parsed
# once into vilslam_pch and reused by every module, the CLI and the benchmarks; the tests reuse
# vilslam_test_pch, the same plus GoogleTest's (tests/CMakeLists.txt). A header the PCH holds still needs its
# own #include where it is used.
option(VILSLAM_PCH "Precompile the common headers (cmake/modules.cmake)" ON)
set(VILSLAM_PCH_HEADERS <algorithm> <cmath> <cstdint> <filesystem> <fstream> <functional> <map> <memory>
    <optional> <sstream> <stdexcept> <string> <vector> <Eigen/Core> <Eigen/Geometry> <opencv2/core.hpp>)
# vilslam_add_pch(<name> [DEPS <targets...>] [HEADERS <headers...>]): the object target <name> that compiles
# VILSLAM_PCH_HEADERS and HEADERS with the library's compile flags and those of DEPS.
function(vilslam_add_pch name)
  if(VILSLAM_PCH)
    cmake_parse_arguments(ARG "" "" "DEPS;HEADERS" ${ARGN})
    add_library(${name} OBJECT ${CMAKE_SOURCE_DIR}/cmake/pch.cpp)
    target_link_libraries(${name} PRIVATE Eigen3::Eigen opencv_core yaml-cpp spdlog::spdlog ${ARG_DEPS})
    target_precompile_headers(${name} PRIVATE ${VILSLAM_PCH_HEADERS} ${ARG_HEADERS})
  endif()
endfunction()
# vilslam_use_pch(<target> [<pch>]): <target> reuses <pch> (default vilslam_pch) when VILSLAM_PCH is on.
function(vilslam_use_pch target)
  if(VILSLAM_PCH)
    set(pch vilslam_pch)
    if(ARGC GREATER 1)
      set(pch ${ARGV1})
    endif()
    target_precompile_headers(${target} REUSE_FROM ${pch})
  endif()
endfunction()

# vilslam_module(<name> DEPS <targets...>)
# Builds src/<name>/*.cpp into the static library vilslam_<name>; a module without sources yet is an
# INTERFACE library so that dependants still configure.
set(VILSLAM_MODULES "")
function(vilslam_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/${name}/*.cpp)
  set(target vilslam_${name})
  if(sources)
    add_library(${target} STATIC ${sources})
    target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}/src>
                                                $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/vilslam>)
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
    vilslam_use_pch(${target})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}/src>
                                                   $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/vilslam>)
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  set(VILSLAM_MODULES ${VILSLAM_MODULES} ${target} PARENT_SCOPE)
endfunction()

# vilslam_embed_text(<target> <symbol> <file>)
# Compiles <file>'s text into <target> as `std::string_view vilslam::embedded::<symbol>()`, regenerated when
# the file changes (cmake/embed_text.cmake).
function(vilslam_embed_text target symbol file)
  set(out ${CMAKE_BINARY_DIR}/embedded/${symbol}.cpp)
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DIN=${file} -DOUT=${out} -DSYMBOL=${symbol} -P ${CMAKE_SOURCE_DIR}/cmake/embed_text.cmake
    DEPENDS ${file} ${CMAKE_SOURCE_DIR}/cmake/embed_text.cmake
    COMMENT "Embedding ${file}")
  target_sources(${target} PRIVATE ${out})
endfunction()
