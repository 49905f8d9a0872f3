# Finds the system packages listed in third_party_config/packages.txt.
find_package(Vulkan 1.3 REQUIRED)
find_package(glslang REQUIRED CONFIG)
find_package(glm REQUIRED CONFIG)
find_package(TinyGLTF REQUIRED CONFIG)
find_package(nlohmann_json REQUIRED CONFIG)
find_package(OpenEXR REQUIRED CONFIG)
find_package(PNG REQUIRED)
find_package(glfw3 REQUIRED CONFIG)
find_package(GTest REQUIRED)
find_package(Threads REQUIRED)

find_path(STB_INCLUDE_DIR stb_image.h PATH_SUFFIXES stb REQUIRED)
add_library(voxgi_stb INTERFACE)
target_include_directories(voxgi_stb SYSTEM INTERFACE ${STB_INCLUDE_DIR})

# Debian's OpenColorIO 2.1 installs its CMake config where find_package does not look
# (/usr/share/cmake); its pkg-config file is reliable.
find_package(PkgConfig REQUIRED)
pkg_check_modules(VOXGI_OCIO REQUIRED IMPORTED_TARGET GLOBAL OpenColorIO)
if(NOT TARGET OpenColorIO::OpenColorIO)
  add_library(OpenColorIO::OpenColorIO ALIAS PkgConfig::VOXGI_OCIO)
endif()
