# A build of technique folders against the libraries of an existing build
# (-DSB_PREBUILT_DIR=<that build> -DSB_UNIT_FOLDERS=<folder;...>): compiles only
# those folders' sources, the embedded shaders and cli/main.cpp, and links
# the prebuilt static libraries; the folders' own tests (test_*.cpp) become
# sb_unit_tests. scripts/check-technique-unit.sh uses it to build copied unit
# folders in seconds instead of rebuilding the tree.
find_package(glm REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)
find_package(Vulkan REQUIRED)
find_package(glslang CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(GTest REQUIRED)
find_package(Threads REQUIRED)
find_package(embree 3 CONFIG REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
pkg_check_modules(GLFW REQUIRED IMPORTED_TARGET glfw3)
add_compile_definitions(GLM_FORCE_DEPTH_ZERO_TO_ONE GLM_ENABLE_EXPERIMENTAL)

# Image files: the prebuilt OpenImageIO module, beside the program that loads it.
file(COPY_FILE ${SB_PREBUILT_DIR}/libsb_oiio.so ${CMAKE_BINARY_DIR}/libsb_oiio.so)

# The prebuilt techniques without their embedded shaders: this build embeds
# every shader of this tree (the new folders' too) in their place.
set(_techniques ${CMAKE_BINARY_DIR}/libsb_techniques_prebuilt.a)
file(COPY_FILE ${SB_PREBUILT_DIR}/libsb_techniques.a ${_techniques})
execute_process(COMMAND ${CMAKE_AR} d ${_techniques} embedded_shaders.cpp.o
                COMMAND_ERROR_IS_FATAL ANY)
foreach(_lib sb_cli sb_harness sb_imaging sb_reports sb_pbr sb_backends sb_scene_units sb_scenes
    sb_base)
  add_library(${_lib} STATIC IMPORTED)
  set_target_properties(${_lib} PROPERTIES IMPORTED_LOCATION ${SB_PREBUILT_DIR}/lib${_lib}.a)
endforeach()
add_library(sb_techniques STATIC IMPORTED)
set_target_properties(sb_techniques PROPERTIES IMPORTED_LOCATION ${_techniques})

file(GLOB_RECURSE SB_SHADER_FILES techniques/*.glsl techniques/*.vert techniques/*.frag
  techniques/*.comp techniques/slots.h techniques/*uniforms.h techniques/unit.json render/*.glsl
  render/*.vert render/*.frag render/*.comp render/*.mesh render/slots.h render/*uniforms.h
  render/common/uniform_block.h render/generation/groom_table.h scenes/groom_rule.h
  base/hash.h)
  # every folder's slots.h, uniforms.h and unit.json (the new folders' too), the generation
  # rule: the same list as CMakeLists.txt's
string(REPLACE ";" "|" SB_SHADER_LIST "${SB_SHADER_FILES}")
set(SB_SHADER_CPP ${CMAKE_BINARY_DIR}/generated/embedded_shaders.cpp)
add_custom_command(
  OUTPUT ${SB_SHADER_CPP}
  COMMAND ${CMAKE_COMMAND} -DSRC_DIR=${CMAKE_SOURCE_DIR} -DOUT=${SB_SHADER_CPP}
          "-DFILES=${SB_SHADER_LIST}" -P ${CMAKE_SOURCE_DIR}/cmake/EmbedShaders.cmake
  DEPENDS ${SB_SHADER_FILES} ${CMAKE_SOURCE_DIR}/cmake/EmbedShaders.cmake VERBATIM)

set(_sources "")
set(_tests "")
# SB_UNIT_FOLDERS: technique folders (techniques/<folder>); SB_SCENE_UNIT_FOLDERS: scene
# generator folders (scenes/generators/<folder>).
set(_folders "")
foreach(_folder IN LISTS SB_UNIT_FOLDERS)
  list(APPEND _folders techniques/${_folder})
endforeach()
foreach(_folder IN LISTS SB_SCENE_UNIT_FOLDERS)
  list(APPEND _folders scenes/generators/${_folder})
endforeach()
foreach(_folder IN LISTS _folders)
  file(GLOB _folder_sources ${_folder}/*.cpp)
  set(_folder_tests ${_folder_sources})
  list(FILTER _folder_tests INCLUDE REGEX "/test_[^/]*\\.cpp$")
  list(FILTER _folder_sources EXCLUDE REGEX "/test_[^/]*\\.cpp$")
  list(APPEND _sources ${_folder_sources})
  list(APPEND _tests ${_folder_tests})
endforeach()
set(_libs sb_cli "$<LINK_LIBRARY:WHOLE_ARCHIVE,sb_harness>" sb_imaging sb_reports sb_pbr
  "$<LINK_LIBRARY:WHOLE_ARCHIVE,sb_techniques>" sb_backends
  "$<LINK_LIBRARY:WHOLE_ARCHIVE,sb_scene_units>" sb_scenes sb_base
  CLI11::CLI11 nlohmann_json::nlohmann_json
  glm::glm tinyobjloader::tinyobjloader Vulkan::Vulkan PkgConfig::EGL PkgConfig::GLFW
  glslang::glslang glslang::SPIRV glslang::glslang-default-resource-limits embree ${CMAKE_DL_LIBS}
  Threads::Threads)
# The new folders' objects and the shaders, once for the program and the tests: each
# registers itself, so they are linked as they are; the prebuilt techniques whole, as in the
# main build.
add_library(sb_units OBJECT ${_sources} ${SB_SHADER_CPP})
target_include_directories(sb_units PRIVATE ${CMAKE_SOURCE_DIR})
target_link_libraries(sb_units PRIVATE glm::glm nlohmann_json::nlohmann_json)
add_executable(strandbench cli/main.cpp $<TARGET_OBJECTS:sb_units>)
target_include_directories(strandbench PRIVATE ${CMAKE_SOURCE_DIR})
target_link_libraries(strandbench PRIVATE ${_libs})
if(_tests)
  add_executable(sb_unit_tests tests/main.cpp ${_tests} $<TARGET_OBJECTS:sb_units>)
  target_include_directories(sb_unit_tests PRIVATE ${CMAKE_SOURCE_DIR} ${CMAKE_SOURCE_DIR}/tests)
  target_compile_definitions(sb_unit_tests PRIVATE
    SB_SOURCE_DIR="${CMAKE_SOURCE_DIR}" SB_CLI="$<TARGET_FILE:strandbench>")
  target_link_libraries(sb_unit_tests PRIVATE ${_libs} GTest::gtest)
  add_dependencies(sb_unit_tests strandbench)
endif()
