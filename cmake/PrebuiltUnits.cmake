# A build of technique folders against the libraries of an existing build
# (-DSB_PREBUILT_DIR=<that build> -DSB_UNIT_FOLDERS=<folder;...>): compiles only
# those folders' sources, the embedded shaders and cli/main.cpp, and links
# the prebuilt static libraries. scripts/check-technique-unit.sh uses it to
# build a copied technique folder in seconds instead of rebuilding the tree.
find_package(glm REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)
find_package(Vulkan REQUIRED)
find_package(glslang CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
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
foreach(_lib sb_cli sb_harness sb_imaging sb_reports sb_pbr sb_backends sb_scenes sb_base)
  add_library(${_lib} STATIC IMPORTED)
  set_target_properties(${_lib} PROPERTIES IMPORTED_LOCATION ${SB_PREBUILT_DIR}/lib${_lib}.a)
endforeach()
add_library(sb_techniques STATIC IMPORTED)
set_target_properties(sb_techniques PROPERTIES IMPORTED_LOCATION ${_techniques})

file(GLOB_RECURSE SB_SHADER_FILES techniques/*.glsl techniques/*.vert techniques/*.frag
  techniques/*.comp techniques/slots.h techniques/*uniforms.h render/*.glsl render/*.vert
  render/*.frag render/*.comp render/slots.h render/*uniforms.h render/common/uniform_block.h
  scenes/groom_rule.h)
  # every folder's slots.h and uniforms.h (the new folders' too)
string(REPLACE ";" "|" SB_SHADER_LIST "${SB_SHADER_FILES}")
set(SB_SHADER_CPP ${CMAKE_BINARY_DIR}/generated/embedded_shaders.cpp)
add_custom_command(
  OUTPUT ${SB_SHADER_CPP}
  COMMAND ${CMAKE_COMMAND} -DSRC_DIR=${CMAKE_SOURCE_DIR} -DOUT=${SB_SHADER_CPP}
          "-DFILES=${SB_SHADER_LIST}" -P ${CMAKE_SOURCE_DIR}/cmake/EmbedShaders.cmake
  DEPENDS ${SB_SHADER_FILES} ${CMAKE_SOURCE_DIR}/cmake/EmbedShaders.cmake VERBATIM)

set(_sources cli/main.cpp ${SB_SHADER_CPP})
foreach(_folder IN LISTS SB_UNIT_FOLDERS)
  file(GLOB _folder_sources techniques/${_folder}/*.cpp)
  list(APPEND _sources ${_folder_sources})
endforeach()
add_executable(strandbench ${_sources})
target_include_directories(strandbench PRIVATE ${CMAKE_SOURCE_DIR})
# The new folders' objects are linked as they are (each registers itself); the
# prebuilt techniques whole, as in the main build.
target_link_libraries(strandbench PRIVATE sb_cli sb_harness sb_imaging sb_reports sb_pbr
  "$<LINK_LIBRARY:WHOLE_ARCHIVE,sb_techniques>" sb_backends sb_scenes sb_base
  CLI11::CLI11 nlohmann_json::nlohmann_json
  glm::glm tinyobjloader::tinyobjloader Vulkan::Vulkan PkgConfig::EGL PkgConfig::GLFW
  glslang::glslang glslang::SPIRV glslang::glslang-default-resource-limits embree ${CMAKE_DL_LIBS}
  Threads::Threads)
